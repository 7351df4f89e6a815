/* bench_search.c: contact-search benchmark: slave points against a wavy
 * master surface of nf facets; prints one CSV row
 * facets,points,build_s,query_s,brute_s,peak_mb
 * (brute_s: unpruned loop timed on a sample of points and scaled to all
 * points; empty when it would take too long). */
#define _POSIX_C_SOURCE 200809L
#include "ffc.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <time.h>

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static double zw(double x, double y) { return 0.05 * sin(6 * x + 1) * sin(4 * y); }

/* n x n cells, two triangles each, on [0,1]^2 with height zw + dz */
static void grid(int n, double dz, double jit, unsigned seed, double **x, long **F, long *nv, long *nf)
{
    *nv = (long)(n + 1) * (n + 1);
    *nf = 2L * n * n;
    *x = malloc(*nv * 3 * sizeof **x);
    *F = malloc(*nf * 3 * sizeof **F);
    srand(seed);
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            double *p = *x + 3 * ((long)j * (n + 1) + i);
            double u = (double)i / n, v = (double)j / n;
            if (i > 0 && j > 0 && i < n && j < n) {
                u += jit * (rand() / (double)RAND_MAX - 0.5) / n;
                v += jit * (rand() / (double)RAND_MAX - 0.5) / n;
            }
            p[0] = u; p[1] = v;
            p[2] = zw(u, v) + dz * (rand() / (double)RAND_MAX - 0.5) / n;
        }
    long f = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            long a = (long)j * (n + 1) + i, b = a + 1, d = a + n + 1, c = d + 1;
            long t[6] = {a, b, d, b, c, d};
            for (int k = 0; k < 6; k++) (*F)[3 * f + k] = t[k];
            f += 2;
        }
}

int main(int argc, char **argv)
{
    long target = argc > 1 ? atol(argv[1]) : 10000;
    long brute_max = argc > 2 ? atol(argv[2]) : 200000;
    int n = (int)lround(sqrt(target / 2.0));
    double *xm, *xs;
    long *Fm, *Fs, nvm, nfm, nvs, nfs;
    grid(n, 0.0, 0.4, 1, &xm, &Fm, &nvm, &nfm);
    grid(n, 1.0, 0.4, 2, &xs, &Fs, &nvs, &nfs); /* slave nodes within +-h/2 of the master */
    ffc_search_opts o = ffc_search_defaults();
    ffc_link *L = malloc(nfs * sizeof *L);

    double t0 = now();
    ffc_tree *t;
    if (ffc_tree_build(3, nfm, Fm, nvm, xm, &t)) return 1;
    double t1 = now();
    int found = ffc_search(t, 3, nfs, Fs, nvs, xs, 1, &o, nfs, L);
    double t2 = now();
    if (found < 0) return 1;

    double brute = -1;
    if (nfm <= brute_max) {
        long ns = nfs < 1000 ? nfs : 1000;
        ffc_link *B = malloc(ns * sizeof *B);
        double b0 = now();
        ffc_search_brute(t, 3, ns, Fs, nvs, xs, 1, &o, ns, B);
        brute = (now() - b0) * (double)nfs / ns;
        for (long k = 0; k < ns; k++)
            if (B[k].mf != L[k].mf && B[k].mf >= 0 && L[k].mf >= 0 && fabs(B[k].gap - L[k].gap) > 1e-12) {
                fprintf(stderr, "mismatch at point %ld\n", k);
                return 1;
            }
        free(B);
    }
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    printf("%ld,%ld,%.4f,%.4f,", nfm, nfs, t1 - t0, t2 - t1);
    if (brute >= 0) printf("%.3f", brute);
    printf(",%.1f\n", ru.ru_maxrss / 1024.0);
    fprintf(stderr, "facets %ld points %ld linked %d tree %.1f MB\n", nfm, nfs, found,
            ffc_tree_bytes(t) / 1048576.0);
    ffc_tree_free(t);
    free(L); free(xm); free(xs); free(Fm); free(Fs);
    return 0;
}
