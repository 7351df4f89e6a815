/* test_mpi_gather.c: every rank's triplets gathered on every rank, in the
 * order of the ranks (run by mpiexec, 2 ranks in make test), summed into
 * the same matrix as one process's; the capacity and a bad argument on
 * one rank answered alike on every rank (no rank left waiting). */
#include <stdio.h>
#include <stdlib.h>

#include <mpi.h>

#include "ffc_test.h"

/* rank r's piece: rows 3r .. 3r + 2 of a chain matrix on n = 3 size + 1
 * dofs, the shared dof 3r + 3 (the next piece's first) on both pieces */
static long piece(int r, long Ti[], long Tj[], double Tv[])
{
    long t = 0;
    for (int e = 0; e < 3; e++) {
        const long a = 3L * r + e, b = a + 1;
        const double k = 1.0 + 0.25 * (double)a;
        const long p[4][2] = {{a, a}, {b, b}, {a, b}, {b, a}};
        const double v[4] = {k, k, -k, -k};
        for (int q = 0; q < 4; q++) { Ti[t] = p[q][0]; Tj[t] = p[q][1]; Tv[t] = v[q]; t++; }
    }
    return t;
}

static void test_gathered_in_rank_order(void **state)
{
    (void)state;
    int rank, size;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    long Ti[12], Tj[12];
    double Tv[12];
    const long nt = piece(rank, Ti, Tj, Tv);
    long total = -1;
    assert_int_equal(ffc_mpi_gather_triplets(nt, Ti, Tj, Tv, 0, NULL, NULL, NULL, &total), FFC_ERR_CAPACITY);
    assert_int_equal(total, 12L * size);
    long *Oi = malloc((size_t)total * sizeof *Oi), *Oj = malloc((size_t)total * sizeof *Oj);
    double *Ov = malloc((size_t)total * sizeof *Ov);
    assert_non_null(Oi); assert_non_null(Oj); assert_non_null(Ov);
    assert_int_equal(ffc_mpi_gather_triplets(nt, Ti, Tj, Tv, total, Oi, Oj, Ov, &total), FFC_OK);
    for (int r = 0; r < size; r++) {   /* rank r's piece at 12 r */
        long Ri[12], Rj[12];
        double Rv[12];
        piece(r, Ri, Rj, Rv);
        for (int k = 0; k < 12; k++) {
            assert_int_equal(Oi[12 * r + k], Ri[k]);
            assert_int_equal(Oj[12 * r + k], Rj[k]);
            assert_close(Ov[12 * r + k], Rv[k], 0.0);
        }
    }
    /* summed: the chain of 3 size springs, one process's matrix */
    const long n = 3L * size + 1;
    long *Ci = malloc((size_t)total * sizeof *Ci), *Cj = malloc((size_t)total * sizeof *Cj);
    long *rp = malloc((size_t)(n + 1) * sizeof *rp), *w = malloc((size_t)n * sizeof *w);
    double *Cv = malloc((size_t)total * sizeof *Cv);
    const long nz = ffc_triplets_sum(n, total, Oi, Oj, Ov, Ci, Cj, Cv, rp, w);
    assert_int_equal(nz, 3 * n - 2);
    for (long t = 0; t < nz; t++) {
        const long a = Ci[t], b = Cj[t];
        const double ka = 1.0 + 0.25 * (double)a, kl = 1.0 + 0.25 * (double)(a - 1);
        double want;
        if (a == b) want = (a < n - 1 ? ka : 0.0) + (a > 0 ? kl : 0.0);
        else want = -(1.0 + 0.25 * (double)(a < b ? a : b));
        assert_close(Cv[t], want, 1e-15);
    }
    free(Oi); free(Oj); free(Ov); free(Ci); free(Cj); free(Cv); free(rp); free(w);
}

static void test_bad_argument_on_one_rank(void **state)
{
    (void)state;
    int rank;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    long Ti[12], Tj[12], Oi[96], Oj[96], total = -1;   /* (up to 8 ranks) */
    double Tv[12], Ov[96];
    const long nt = piece(rank, Ti, Tj, Tv);
    /* rank 1 passes no values: both ranks get FFC_ERR_NULL */
    const double *v = rank == 1 ? NULL : Tv;
    assert_int_equal(ffc_mpi_gather_triplets(nt, Ti, Tj, v, 96, Oi, Oj, Ov, &total), FFC_ERR_NULL);
    /* rank 0 a negative count, rank 1 no values: the most negative status */
    const long m = rank == 0 ? -1 : nt;
    const int want = FFC_ERR_NULL < FFC_ERR_SIZE ? FFC_ERR_NULL : FFC_ERR_SIZE;
    assert_int_equal(ffc_mpi_gather_triplets(m, Ti, Tj, v, 96, Oi, Oj, Ov, &total), want);
    /* rank 0's capacity too small: every rank is told */
    assert_int_equal(ffc_mpi_gather_triplets(nt, Ti, Tj, Tv, rank == 0 ? 4 : 96, Oi, Oj, Ov, &total), FFC_ERR_CAPACITY);
    /* and then it works */
    assert_int_equal(ffc_mpi_gather_triplets(nt, Ti, Tj, Tv, 96, Oi, Oj, Ov, &total), FFC_OK);
}

int main(int argc, char **argv)
{
    MPI_Init(&argc, &argv);
    int rank;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank > 0 && !freopen("/dev/null", "w", stdout)) return 1; /* one report */
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_gathered_in_rank_order),
        cmocka_unit_test(test_bad_argument_on_one_rank),
    };
    const int failed = cmocka_run_group_tests(tests, NULL, NULL);
    MPI_Finalize();
    return failed;
}
