/* fuzz_project.c: libFuzzer target for the closest-point projection and
 * its derivatives: any facet and point built from the input bytes; the
 * kernels must not crash, must return a status, and their results must keep
 * the projection's invariants (abort otherwise). */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ffc.h"

static double coord(const uint8_t *d)
{
    int16_t v;
    memcpy(&v, d, 2);
    return v / 3276.8; /* [-10, 10] */
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1 + 2 * 3 * 7) return 0;
    const int nn = (data[0] & 1) ? 6 : 3;
    double X[6][3], p[3];
    const uint8_t *d = data + 1;
    for (int a = 0; a < 6; a++)
        for (int i = 0; i < 3; i++, d += 2) X[a][i] = coord(d);
    for (int i = 0; i < 3; i++, d += 2) p[i] = coord(d);
    if (nn == 6 && (data[0] & 2)) /* mid-edge nodes near the midpoints: mildly curved facets */
        for (int e = 0; e < 3; e++)
            for (int i = 0; i < 3; i++)
                X[3 + e][i] = 0.5 * (X[e][i] + X[(e + 1) % 3][i]) + 0.05 * X[3 + e][i];
    ffc_proj pr;
    int st = ffc_project(nn, (const double(*)[3])X, p, &pr);
    if (st < 0) {
        if (!ffc_strerror(st)) abort();
        return 0;
    }
    if (!isfinite(pr.dist) || !isfinite(pr.gap) || pr.dist < 0) abort();
    if (fabs(pr.gap) > pr.dist * (1 + 1e-9) + 1e-9) abort();
    if (pr.xi[0] < -1e-9 || pr.xi[1] < -1e-9 || pr.xi[0] + pr.xi[1] > 1 + 1e-9) abort();
    double nrm = sqrt(pr.n[0] * pr.n[0] + pr.n[1] * pr.n[1] + pr.n[2] * pr.n[2]);
    if (fabs(nrm - 1) > 1e-9) abort();
    /* the closest point is no farther than any vertex of the facet (the
     * vertices lie on it); for flat facets exactly, for curved ones only
     * when the Newton converged to the global minimum, so flat only */
    if (nn == 3)
        for (int a = 0; a < 3; a++) {
            double dx = p[0] - X[a][0], dy = p[1] - X[a][1], dz = p[2] - X[a][2];
            if (pr.dist > sqrt(dx * dx + dy * dy + dz * dz) * (1 + 1e-9) + 1e-9) abort();
        }
    if (pr.where == FFC_FOOT_INSIDE) {
        const double Ns[3] = {0.2, 0.3, 0.5};
        double dxi[2][FFC_MAXDOF], dg[FFC_MAXDOF], dn[3][FFC_MAXDOF];
        int sd = ffc_project_deriv(3, Ns, nn, (const double(*)[3])X, &pr, dxi, dg, dn);
        if (sd == FFC_OK)
            for (int k = 0; k < 3 * (3 + nn); k++)
                if (!isfinite(dg[k])) abort();
    }
    return 0;
}
