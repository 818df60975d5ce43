/* Temperatures and temperature-dependent material properties on the host:
 * the value of a property (a constant or a [T, value] table), the reference
 * density rho0(T) of the isothermally incompressible fluid (Russell 2018
 * Sec. 3.4, Eq. 3.52; the kernels evaluate it with the same rule,
 * kernels/materials.h) and the prescribed temperature history. */
#ifndef AMSPH_MATERIAL_H
#define AMSPH_MATERIAL_H

#include "case.h"

/* Value of a property at temperature t: the constant, or linear between the
 * table's points and constant beyond its ends. */
double amsph_property_value(const amsph_property *p, double t);

/* Reference density rho0(T) of the material, kg/m^3. */
double amsph_material_density(const amsph_material *m, double t);

/* Smallest and largest rho0 of the material over all temperatures. */
void amsph_material_density_bounds(const amsph_material *m, double *lowest, double *highest);

/* 1 when rho0 depends on the temperature (a table of two or more points). */
int amsph_material_density_varies(const amsph_material *m);

/* The prescribed uniform temperature at time t, K (case.h). */
double amsph_temperature_history_at(const amsph_temperature_history *h, double t);

#endif
