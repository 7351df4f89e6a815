/* test_petsc_ranks.c: the iterative path (PETSc) with its rows shared
 * out over the ranks of MPI_COMM_WORLD (mpiexec, 2 ranks in make test):
 * the same solution as UMFPACK's in one process, on every rank, by GAMG
 * and BoomerAMG (within cond x rtol) and MUMPS through PETSc (round-off),
 * and with an exact block; a non-convergence reported alike on every
 * rank. */
#include <stdio.h>

#include <mpi.h>

#include "petsc_test.h"

static pb_system sys;
static double x0[PB_N];

static int setup(void **state)
{
    (void)state;
    pb_make(&sys);
    ffc_full *f = NULL;
    if (ffc_full_create(&f)) return -1;
    const int st = ffc_full_solve(f, PB_N, sys.nt, sys.Ti, sys.Tj, sys.Tv, 0, sys.b, x0, NULL);
    ffc_full_free(f);
    return st;
}

static ffc_full *iterative(int pc, double rtol, long maxit)
{
    int fc, size;
    ffc_mpi_world(NULL, &size, &fc);
    assert_true(size >= 2);
    ffc_full *f = NULL;
    assert_int_equal(ffc_full_create(&f), FFC_OK);
    const ffc_iterative o = {1, 1, fc, pc, rtol, maxit, PB_NV, sys.X};
    assert_int_equal(ffc_full_set_iterative(f, &o), FFC_OK);
    return f;
}

/* every rank's x against UMFPACK's (1e-6: the box's condition number is
 * below 1e4, rtol 1e-10; MUMPS 1e-12), and the ranks' x the same bits */
static void test_same_solution(void **state)
{
    (void)state;
    static double x[PB_N], y[PB_N];
    for (int pc = 0; pc < 3; pc++) {
        ffc_full *f = iterative(pc, 1e-10, 500);
        ffc_solve_info info;
        assert_int_equal(ffc_full_solve(f, PB_N, sys.nt, sys.Ti, sys.Tj, sys.Tv, 0, sys.b, x, NULL), FFC_OK);
        assert_int_equal(ffc_full_info(f, &info, NULL, NULL, NULL), FFC_OK);
        assert_int_equal(info.ranks, 2);
        const double d = pb_diff(x, x0);
        printf("  pc %d on 2 ranks: against UMFPACK %.2e, residual %.2e\n", pc, d, pb_residual(&sys, x));
        assert_true(d <= (pc == FFC_PC_MUMPS ? 1e-12 : 1e-6));
        MPI_Allreduce(x, y, PB_N, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
        for (long i = 0; i < PB_N; i++) assert_true(x[i] == y[i]);
        ffc_full_free(f);
    }
}

/* the top face's dofs solved exactly after each multigrid cycle (one LU
 * over both ranks): the same solution */
static void test_block(void **state)
{
    (void)state;
    static double x[PB_N];
    static long dofs[PB_N];
    const long nb = pb_top_dofs(dofs);
    ffc_full *f = iterative(FFC_PC_GAMG, 1e-10, 500);
    assert_int_equal(ffc_full_set_block(f, PB_N, nb, dofs), FFC_OK);
    assert_int_equal(ffc_full_solve(f, PB_N, sys.nt, sys.Ti, sys.Tj, sys.Tv, 0, sys.b, x, NULL), FFC_OK);
    assert_true(pb_diff(x, x0) <= 1e-6);
    assert_true(pb_residual(&sys, x) <= 1e-10);
    ffc_full_free(f);
}

static void test_not_converged(void **state)
{
    (void)state;
    static double x[PB_N];
    ffc_full *f = iterative(FFC_PC_GAMG, 1e-14, 2);
    ffc_error err = {0};
    assert_int_equal(ffc_full_solve(f, PB_N, sys.nt, sys.Ti, sys.Tj, sys.Tv, 0, sys.b, x, &err), FFC_ERR_NOCONV);
    assert_non_null(strstr(err.msg, "did not converge in 2 iterations"));
    ffc_full_free(f);
}

int main(int argc, char **argv)
{
    MPI_Init(&argc, &argv);
    int rank;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank > 0 && !freopen("/dev/null", "w", stdout)) return 1; /* one report */
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_same_solution), cmocka_unit_test(test_block),
                                       cmocka_unit_test(test_not_converged)};
    const int failed = cmocka_run_group_tests(tests, setup, NULL);
    MPI_Finalize();
    return failed;
}
