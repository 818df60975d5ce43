#include "evaporation.h"

#include <math.h>

#include "error.h"

static amsph_arg field(amsph_sim *s, amsph_field_id f)
{
    return amsph_arg_buffer(s->particles.field[f]);
}

int amsph_evaporation_recoil(amsph_sim *s)
{
    const int n = s->particles.n;
    return AMSPH_LAUNCH(s->backend, "recoil_force", n, field(s, AMSPH_FIELD_POSITION),
                        field(s, AMSPH_FIELD_DENSITY), field(s, AMSPH_FIELD_MASS),
                        field(s, AMSPH_FIELD_TEMPERATURE), field(s, AMSPH_FIELD_KIND),
                        field(s, AMSPH_FIELD_MATERIAL), amsph_arg_buffer(s->grid.cell), amsph_arg_int(n),
                        amsph_arg_bytes(&s->grid.geometry, sizeof s->grid.geometry),
                        amsph_arg_buffer(s->grid.cell_start), amsph_arg_buffer(s->materials),
                        amsph_arg_bytes(&s->thermal, sizeof s->thermal), field(s, AMSPH_FIELD_ACCELERATION));
}

int amsph_evaporation_remove_hot(amsph_sim *s)
{
    amsph_particles *p = &s->particles;
    amsph_buffer *leaving = s->thermal_work.evaporated;
    const int n = p->n;
    AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "evaporate_hot", n, field(s, AMSPH_FIELD_KIND),
                             field(s, AMSPH_FIELD_TEMPERATURE), field(s, AMSPH_FIELD_MASS),
                             field(s, AMSPH_FIELD_ENTHALPY), amsph_arg_int(n),
                             amsph_arg_bytes(&s->thermal, sizeof s->thermal), field(s, AMSPH_FIELD_POSITION),
                             amsph_arg_buffer(s->work), amsph_arg_buffer(leaving)));
    double count = 0.0, enthalpy = 0.0;
    AMSPH_CHECK(amsph_reduce_sum(s->backend, leaving, n, &count));
    if (count == 0.0)
        return 0;
    AMSPH_CHECK(amsph_reduce_sum(s->backend, s->work, n, &enthalpy));
    /* the sort drops the particles just marked, as not finite */
    AMSPH_CHECK(amsph_grid_sort(&s->grid, p));
    if (s->grid.not_finite != (int)llround(count))
        return amsph_fail("step %lld: %lld particles evaporated but the sort dropped %d", s->step,
                          (long long)llround(count), s->grid.not_finite);
    s->evaporated_particles += s->grid.not_finite;
    s->ledger.evaporated += enthalpy;
    return 0;
}
