/* Mobile powder grains (Fuchs et al. 2022 §2.2, §3.4; kernels/grains.cl):
 * rigid bodies of particles of kind `grain`, one per geometry block of that
 * kind and one per grain of a powder bed of that kind. The fluid pushes
 * them, they push back (the reaction of every pair force, so momentum is
 * exchanged exactly), they touch each other, walls and fixed solids through
 * a spring and dashpot, and with the thermal module their particles melt
 * into the fluid and solidifying fluid joins the grain it touches.
 *
 * The grain records live on the device. Their velocities and centres follow
 * from the particles (the particles move rigidly, so the sums over them
 * give the grain back exactly), which is also how a restart recovers them. */
#ifndef AMSPH_GRAINS_HOST_H
#define AMSPH_GRAINS_HOST_H

#include "sim.h"

/* Counts the grains of the scene (the `grain` field) and fills the settings. */
int amsph_grains_setup(amsph_sim *s, amsph_host_particles *h);
int amsph_grains_allocate(amsph_sim *s);
void amsph_grains_free(amsph_sim *s);

/* Half a kick of the grains, and their particles' rigid velocities. */
int amsph_grains_kick(amsph_sim *s, double half_dt);
/* Moves the grain particles and centres over dt (after the fluid's drift). */
int amsph_grains_drift(amsph_sim *s, double dt);
/* The grain particles' forces (after the fluid forces). */
int amsph_grains_forces(amsph_sim *s);
/* The grains' sums of their particles' forces (after every module that
 * adds to them: the surface module's reaction). */
int amsph_grains_sum_forces(amsph_sim *s);
/* The grains' sums from the particles as they are, their angular velocity
 * recovered from the particles' angular momentum. */
int amsph_grains_recover(amsph_sim *s);
/* The grain records for a saved state (*values reals, malloc'd into
 * *records), and back into a restored sim, which continues bit for bit. */
int amsph_grains_save(amsph_sim *s, amsph_real **records, int *values);
int amsph_grains_restore(amsph_sim *s, const amsph_real *records, int values);
/* Grain particles that melted leave, solidifying fluid joins (thermal
 * module, before its own phase change). */
int amsph_grains_change_phase(amsph_sim *s);
/* The contact limit 0.22 sqrt(m / k_c) (Fuchs Eq. 42). */
void amsph_grains_dt(const amsph_sim *s, double *dt, const char **limit);
/* The grain records, s->grains.count x GRAIN_RECORD values (kernels/grain_params.h). */
int amsph_grains_download(amsph_sim *s, amsph_real *records);

#endif
