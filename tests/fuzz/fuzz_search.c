/* fuzz_search.c: libFuzzer target for the contact search: a master grid
 * surface with heights from the input bytes and slave points above it; the
 * tree search must equal the all-facet loop link by link (abort otherwise)
 * and never crash. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "ffc.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 4) return 0;
    const int n = 2 + data[0] % 6, m = 2 + data[1] % 6; /* master cells */
    const int ns = 1 + data[2] % 8;                       /* slave facets in a row */
    const double crel = (data[3] % 8) * 0.5;
    size_t pos = 4;
#define BYTE() (pos < size ? data[pos++] : 0)
    const long nvm = (long)(n + 1) * (m + 1), nfm = 2L * n * m, nvs = 3L * ns;
    double *x = malloc((size_t)(nvm + nvs) * 3 * sizeof *x);
    long *Fm = malloc((size_t)nfm * 3 * sizeof *Fm), *Fs = malloc((size_t)ns * 3 * sizeof *Fs);
    if (!x || !Fm || !Fs) { free(x); free(Fm); free(Fs); return 0; }
    for (int j = 0; j <= m; j++)
        for (int i = 0; i <= n; i++) {
            double *p = x + 3 * (j * (n + 1) + i);
            p[0] = (double)i / n + (BYTE() - 128) * 0.002 / n;
            p[1] = (double)j / m + (BYTE() - 128) * 0.002 / m;
            p[2] = (BYTE() - 128) * 0.002;
        }
    long f = 0;
    for (int j = 0; j < m; j++)
        for (int i = 0; i < n; i++) {
            long a = j * (n + 1) + i, b = a + 1, d = a + n + 1, c = d + 1;
            Fm[3 * f] = a; Fm[3 * f + 1] = b; Fm[3 * f + 2] = d; f++;
            Fm[3 * f] = b; Fm[3 * f + 1] = c; Fm[3 * f + 2] = d; f++;
        }
    /* slave: small triangles anywhere in [-0.5, 1.5]^2 x [-0.5, 0.5] */
    for (int s = 0; s < ns; s++) {
        double cx = -0.5 + BYTE() / 128.0, cy = -0.5 + BYTE() / 128.0, cz = (BYTE() - 128) / 256.0;
        for (int a = 0; a < 3; a++) {
            double *p = x + 3 * (nvm + 3 * s + a);
            p[0] = cx + 0.05 * (a == 1);
            p[1] = cy + 0.05 * (a == 2);
            p[2] = cz;
            Fs[3 * s + a] = nvm + 3 * s + a;
        }
    }
#undef BYTE
    ffc_tree *t = NULL;
    if (ffc_tree_build(3, nfm, Fm, nvm + nvs, x, &t) == FFC_OK) {
        ffc_search_opts o = ffc_search_defaults();
        o.capture_rel = crel;
        const int nq = 3;
        ffc_link A[8 * 3], B[8 * 3];
        int fa = ffc_search(t, 3, ns, Fs, nvm + nvs, x, 2, &o, ns * nq, A);
        int fb = ffc_search_brute(t, 3, ns, Fs, nvm + nvs, x, 2, &o, ns * nq, B);
        if (fa != fb) abort();
        for (int k = 0; fa >= 0 && k < ns * nq; k++) {
            if (A[k].mf != B[k].mf) abort();
            if (A[k].mf >= 0 && fabs(A[k].gap - B[k].gap) > 1e-12 * (1 + fabs(B[k].gap))) abort();
        }
        ffc_tree_free(t);
    }
    free(x); free(Fm); free(Fs);
    return 0;
}
