/* Reductions in two stages with a fixed chunking: each item reduces one chunk
 * of `chunk` values, the host combines the partials. The chunking does not
 * depend on the thread count or the device, so sums are reproducible. */
#include "device.h"

#define REDUCE_SUM 0
#define REDUCE_MAX 1
#define REDUCE_MIN 2

KERNEL void reduce_chunks(GLOBAL const real *x, int n, int chunk, int nchunks, int op,
                          GLOBAL real *partial)
{
    FOR_EACH_ITEM(k, nchunks)
    {
        const int begin = k * chunk;
        const int end = begin + chunk < n ? begin + chunk : n;
        real acc = op == REDUCE_MAX ? -INFINITY : op == REDUCE_MIN ? INFINITY : REAL(0.0);
        real compensation = REAL(0.0); /* Kahan summation */
        for (int j = begin; j < end; ++j) {
            if (op == REDUCE_MAX) {
                acc = fmax(acc, x[j]);
            } else if (op == REDUCE_MIN) {
                acc = fmin(acc, x[j]);
            } else {
                const real y = x[j] - compensation;
                const real t = acc + y;
                compensation = (t - acc) - y;
                acc = t;
            }
        }
        partial[k] = acc;
    }
}
