#include "material.h"

#include <math.h>

#define PI 3.14159265358979323846

double amsph_property_value(const amsph_property *p, double t)
{
    if (p->n == 1 || t <= p->T[0])
        return p->v[0];
    for (int i = 1; i < p->n; ++i)
        if (t < p->T[i])
            return p->v[i - 1] + (t - p->T[i - 1]) * (p->v[i] - p->v[i - 1]) / (p->T[i] - p->T[i - 1]);
    return p->v[p->n - 1];
}

double amsph_material_density(const amsph_material *m, double t)
{
    return amsph_property_value(&m->density, t);
}

/* The extremes of a piecewise-linear table lie at its points. */
void amsph_material_density_bounds(const amsph_material *m, double *lowest, double *highest)
{
    *lowest = m->density.v[0];
    *highest = m->density.v[0];
    for (int i = 1; i < m->density.n; ++i) {
        *lowest = fmin(*lowest, m->density.v[i]);
        *highest = fmax(*highest, m->density.v[i]);
    }
}

int amsph_material_density_varies(const amsph_material *m)
{
    return m->density.n >= 2;
}

double amsph_temperature_history_at(const amsph_temperature_history *h, double t)
{
    if (h->form == AMSPH_HISTORY_SINE)
        return h->reference + h->amplitude * sin(2.0 * PI * h->frequency * t);
    return h->reference + h->amplitude * fmin(t / h->duration, 1.0);
}
