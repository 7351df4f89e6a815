/* bench_pair.c: what N processes at once get from this machine, against
 * one: a dense matrix product (compute-bound, BLAS dgemm) and a streamed
 * update (memory-bound, a[i] += s b[i] over 256 MB), each run alone, then
 * N copies at once; prints the throughput ratio (N x the time alone / the
 * slowest copy's time), the ceiling of any N-rank speedup of work of
 * that kind.
 *   bench_pair [N]   (default 2) */
#include <stdio.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

void dgemm_(const char *, const char *, const int *, const int *, const int *, const double *, const double *,
            const int *, const double *, const int *, const double *, double *, const int *);

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* one kernel's run: its wall time (s), or a negative value */
static double kernel(int which)
{
    if (which == 0) {
        const int n = 1200;
        double *a = malloc(sizeof(double) * n * n), *b = malloc(sizeof(double) * n * n),
               *c = malloc(sizeof(double) * n * n), one = 1, zero = 0;
        if (!a || !b || !c) return -1;
        for (long i = 0; i < (long)n * n; i++) { a[i] = 1e-3 * (double)(i % 7); b[i] = 1e-3 * (double)(i % 5); }
        const double t0 = now();
        for (int r = 0; r < 8; r++) dgemm_("N", "N", &n, &n, &n, &one, a, &n, b, &n, &zero, c, &n);
        const double t = now() - t0;
        const double keep = c[7];
        free(a); free(b); free(c);
        return keep < 0 ? -1 : t;
    }
    const long n = 1L << 24; /* 2 x 128 MB */
    double *a = malloc(sizeof(double) * n), *b = malloc(sizeof(double) * n);
    if (!a || !b) return -1;
    for (long i = 0; i < n; i++) { a[i] = (double)i; b[i] = 1.0; }
    const double t0 = now();
    for (int r = 0; r < 20; r++)
        for (long i = 0; i < n; i++) a[i] += 0.5 * b[i];
    const double t = now() - t0;
    const double keep = a[n / 2];
    free(a); free(b);
    return keep < 0 ? -1 : t;
}

/* N copies at once: the slowest copy's time */
static double together(int which, int np)
{
    int fd[2];
    if (pipe(fd)) return -1;
    for (int p = 0; p < np; p++) {
        const pid_t pid = fork();
        if (pid < 0) return -1;
        if (pid == 0) {
            const double t = kernel(which);
            if (write(fd[1], &t, sizeof t) != (ssize_t)sizeof t) _exit(1);
            _exit(0);
        }
    }
    double worst = 0;
    for (int p = 0; p < np; p++) {
        double t = -1;
        if (read(fd[0], &t, sizeof t) != (ssize_t)sizeof t || t < 0) worst = -1;
        else if (worst >= 0 && t > worst) worst = t;
    }
    while (wait(NULL) > 0) {}
    close(fd[0]); close(fd[1]);
    return worst;
}

int main(int argc, char **argv)
{
    const int np = argc > 1 ? atoi(argv[1]) : 2;
    if (np < 1) { fprintf(stderr, "bench_pair: N = %s must be >= 1\n", argv[1]); return 2; }
    const char *name[2] = {"dgemm (compute)", "streamed update (memory)"};
    for (int k = 0; k < 2; k++) {
        const double t1 = kernel(k), tn = together(k, np);
        if (t1 < 0 || tn < 0) { fprintf(stderr, "bench_pair: %s failed\n", name[k]); return 1; }
        printf("%-26s alone %.3f s, %d at once %.3f s each: %d processes give %.2fx one's throughput\n", name[k], t1,
               np, tn, np, np * t1 / tn);
    }
    return 0;
}
