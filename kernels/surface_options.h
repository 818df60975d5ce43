/* Choices of the surface module, shared by the case parser and the kernels. */
#ifndef AMSPH_SURFACE_OPTIONS_H
#define AMSPH_SURFACE_OPTIONS_H

/* The form of the tension (surface.tension_form, kernels/surface.cl surface_force). */
#define TENSION_FORM_CSF 0    /* the CSF force on each liquid particle (Russell 2018 Eq. 3.31; Fuchs et al. 2022 Eq. 24) */
#define TENSION_FORM_CONSERVATIVE 1 /* the CSF force with the difference to the capillary stress's divergence
                                       shared out: no net force on a closed body of liquid */

#endif
