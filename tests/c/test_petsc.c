/* test_petsc.c: the full solver's iterative path (PETSc) in one process
 * against its direct one (UMFPACK) on an elastic box with an
 * unsymmetric coupling: GMRES with GAMG (the rigid-body modes), with
 * BoomerAMG, and MUMPS through PETSc; the residual it claims; the pattern
 * kept across matrices; an exact block after the multigrid; imposed
 * values exact whatever the tolerance; non-convergence and bad options as statuses
 * with a message; a build without PETSc says so. */
#include <stdio.h>

#include "petsc_test.h"

static pb_system sys;
static double x0[PB_N];   /* UMFPACK's solution */

static int setup(void **state)
{
    (void)state;
    pb_make(&sys);
    ffc_full *f = NULL;
    ffc_error err = {0};
    if (ffc_full_create(&f)) return -1;
    const int st = ffc_full_solve(f, PB_N, sys.nt, sys.Ti, sys.Tj, sys.Tv, 0, sys.b, x0, &err);
    ffc_full_free(f);
    return st;
}

static ffc_full *iterative(int pc, double rtol, long maxit, int modes)
{
    ffc_full *f = NULL;
    assert_int_equal(ffc_full_create(&f), FFC_OK);
    const ffc_iterative o = {1, 0, 0, pc, rtol, maxit, modes ? PB_NV : 0, modes ? sys.X : NULL};
    assert_int_equal(ffc_full_set_iterative(f, &o), FFC_OK);
    return f;
}

/* GAMG and BoomerAMG: a true residual within rtol (1e-10), hence within
 * cond x rtol of UMFPACK's solution (the box's condition number is below
 * 1e4: 1e-6 bounds it with margin); MUMPS: UMFPACK's to 1e-12 (two
 * direct solves, round-off apart), its factors applied once */
static void test_same_solution(void **state)
{
    (void)state;
    if (!ffc_has_petsc()) skip();
    static double x[PB_N];
    const char *name[] = {"GAMG", "BoomerAMG", "MUMPS"};
    for (int pc = 0; pc < 3; pc++) {
        ffc_full *f = iterative(pc, 1e-10, 500, 1);
        ffc_error err = {0};
        assert_int_equal(ffc_full_solve(f, PB_N, sys.nt, sys.Ti, sys.Tj, sys.Tv, 0, sys.b, x, &err), FFC_OK);
        ffc_iterative_info in;
        assert_int_equal(ffc_full_iterative_info(f, &in), FFC_OK);
        const double r = pb_residual(&sys, x), d = pb_diff(x, x0);
        printf("  %s: %ld iterations, residual %.2e, against UMFPACK %.2e\n", name[pc], in.iterations, r, d);
        assert_int_equal(in.setups, 1);
        assert_int_equal(in.solves, 1);
        if (pc == FFC_PC_MUMPS) {
            assert_true(d <= 1e-12);
            assert_int_equal(in.iterations, 1);   /* (one application of the factors) */
        } else {
            assert_true(r <= 1e-10);
            assert_true(d <= 1e-6);
            assert_true(in.iterations > 0);
        }
        /* the imposed value kept: the tgv row's x is its value */
        assert_close(x[3 * pb_node(2, 2, 0)], 0.01, 1e-12);
        ffc_full_free(f);
    }
}

/* a loose tolerance (1e-3): the free dofs off by about that, the imposed
 * values exact (b_i / tgv, not GMRES's), so that Newton's Dirichlet test
 * can pass on a loose linear solve */
static void test_dirichlet_exact(void **state)
{
    (void)state;
    if (!ffc_has_petsc()) skip();
    static double x[PB_N];
    ffc_full *f = iterative(FFC_PC_GAMG, 1e-3, 500, 1);
    assert_int_equal(ffc_full_solve(f, PB_N, sys.nt, sys.Ti, sys.Tj, sys.Tv, 0, sys.b, x, NULL), FFC_OK);
    assert_true(pb_residual(&sys, x) <= 1e-3);
    assert_true(pb_diff(x, x0) > 1e-9);   /* (a loose solve indeed) */
    for (int j = 0; j <= PB_C; j++)
        for (int i = 0; i <= PB_C; i++)
            for (int c = 0; c < 3; c++) {
                const long d = 3 * pb_node(i, j, 0) + c;
                assert_close(x[d], sys.b[d] / PB_TGV, 1e-15 * fabs(sys.b[d] / PB_TGV));
            }
    ffc_full_free(f);
}

/* the rigid-body modes cut GAMG's iterations against the translations
 * alone (elasticity's near-null space has the rotations too) */
static void test_rigid_modes(void **state)
{
    (void)state;
    if (!ffc_has_petsc()) skip();
    static double x[PB_N];
    long its[2];
    for (int m = 0; m < 2; m++) {
        ffc_full *f = iterative(FFC_PC_GAMG, 1e-10, 500, m);
        assert_int_equal(ffc_full_solve(f, PB_N, sys.nt, sys.Ti, sys.Tj, sys.Tv, 0, sys.b, x, NULL), FFC_OK);
        ffc_iterative_info in;
        ffc_full_iterative_info(f, &in);
        its[m] = in.iterations;
        ffc_full_free(f);
    }
    printf("  GAMG: %ld iterations with the translations, %ld with the rigid-body modes\n", its[0], its[1]);
    assert_true(its[1] < its[0]);
}

/* a second matrix on the same pattern, and one with an entry outside it:
 * the pattern kept, then grown; each solve right; the symmetric path
 * stays CHOLMOD's */
static void test_patterns(void **state)
{
    (void)state;
    if (!ffc_has_petsc()) skip();
    static double x[PB_N];
    ffc_full *f = iterative(FFC_PC_GAMG, 1e-10, 500, 1);
    long analyses = 0;
    ffc_solve_info info;
    assert_int_equal(ffc_full_solve(f, PB_N, sys.nt, sys.Ti, sys.Tj, sys.Tv, 0, sys.b, x, NULL), FFC_OK);
    for (long k = 0; k < sys.nt; k++) sys.Tv[k] *= 2.0;
    assert_int_equal(ffc_full_solve(f, PB_N, sys.nt, sys.Ti, sys.Tj, sys.Tv, 0, sys.b, x, NULL), FFC_OK);
    for (long k = 0; k < sys.nt; k++) sys.Tv[k] /= 2.0;
    for (long i = 0; i < PB_N; i++) x[i] *= 2.0;   /* (2 A) x = b: x = x0 / 2 */
    assert_true(pb_diff(x, x0) <= 1e-6);
    assert_int_equal(ffc_full_info(f, &info, &analyses, NULL, NULL), FFC_OK);
    assert_int_equal(analyses, 1);
    /* a coupling across the box (outside the pattern), then taken away */
    const long a = 3 * pb_node(0, 0, PB_C) + 2, b = 3 * pb_node(PB_C, PB_C, PB_C) + 2;
    sys.Ti[sys.nt] = a; sys.Tj[sys.nt] = b; sys.Tv[sys.nt] = -0.1;
    sys.Ti[sys.nt + 1] = a; sys.Tj[sys.nt + 1] = a; sys.Tv[sys.nt + 1] = 0.1;
    sys.nt += 2;
    assert_int_equal(ffc_full_solve(f, PB_N, sys.nt, sys.Ti, sys.Tj, sys.Tv, 0, sys.b, x, NULL), FFC_OK);
    assert_true(pb_residual(&sys, x) <= 1e-10);
    sys.nt -= 2;
    assert_int_equal(ffc_full_info(f, &info, &analyses, NULL, NULL), FFC_OK);
    assert_int_equal(analyses, 2);
    ffc_iterative_info in;
    ffc_full_iterative_info(f, &in);
    assert_int_equal(in.setups, 3);
    assert_int_equal(info.factorizations, 3);
    ffc_full_free(f);
}

/* a block solved exactly after each multigrid cycle (the top face's
 * dofs, where the coupling is): the same solution, in no more iterations
 * than the multigrid alone; a bad block refused */
static void test_block(void **state)
{
    (void)state;
    if (!ffc_has_petsc()) skip();
    static double x[PB_N];
    static long dofs[PB_N];
    const long nb = pb_top_dofs(dofs);
    long its[2];
    for (int b = 0; b < 2; b++) {
        ffc_full *f = iterative(FFC_PC_GAMG, 1e-10, 500, 1);
        assert_int_equal(ffc_full_set_block(f, PB_N, b ? nb : 0, dofs), FFC_OK);
        assert_int_equal(ffc_full_solve(f, PB_N, sys.nt, sys.Ti, sys.Tj, sys.Tv, 0, sys.b, x, NULL), FFC_OK);
        assert_true(pb_residual(&sys, x) <= 1e-10);
        assert_true(pb_diff(x, x0) <= 1e-6);
        ffc_iterative_info in;
        ffc_full_iterative_info(f, &in);
        its[b] = in.iterations;
        if (b) {
            long bad[2] = {5, 5};
            assert_int_equal(ffc_full_set_block(f, PB_N, 2, bad), FFC_ERR_INDEX);
            bad[1] = PB_N;
            assert_int_equal(ffc_full_set_block(f, PB_N, 2, bad), FFC_ERR_INDEX);
            assert_int_equal(ffc_full_set_block(f, PB_N, -1, bad), FFC_ERR_SIZE);
        }
        ffc_full_free(f);
    }
    printf("  GAMG: %ld iterations alone, %ld with the top face's block\n", its[0], its[1]);
    assert_true(its[1] <= its[0]);
}

/* too few iterations: FFC_ERR_NOCONV, the message naming the iterations
 * and the residual reached; bad options refused, the solver unchanged */
static void test_reasons(void **state)
{
    (void)state;
    if (!ffc_has_petsc()) {
        ffc_full *f = NULL;
        assert_int_equal(ffc_full_create(&f), FFC_OK);
        const ffc_iterative o = {1, 0, 0, FFC_PC_GAMG, 1e-8, 100, 0, NULL};
        assert_int_equal(ffc_full_set_iterative(f, &o), FFC_ERR_UNAVAILABLE);
        ffc_full_free(f);
        return;
    }
    static double x[PB_N];
    ffc_full *f = iterative(FFC_PC_GAMG, 1e-14, 2, 1);
    ffc_error err = {0};
    assert_int_equal(ffc_full_solve(f, PB_N, sys.nt, sys.Ti, sys.Tj, sys.Tv, 0, sys.b, x, &err), FFC_ERR_NOCONV);
    printf("  %s\n", err.msg);
    assert_non_null(strstr(err.msg, "did not converge in 2 iterations"));
    assert_non_null(strstr(err.msg, "rtol 1e-14"));
    ffc_iterative o = {1, 0, 0, FFC_PC_GAMG, 0.0, 100, 0, NULL};
    assert_int_equal(ffc_full_set_iterative(f, &o), FFC_ERR_VALUE);
    o.rtol = 1e-8; o.maxit = 0;
    assert_int_equal(ffc_full_set_iterative(f, &o), FFC_ERR_VALUE);
    o.maxit = 100; o.pc = 7;
    assert_int_equal(ffc_full_set_iterative(f, &o), FFC_ERR_VALUE);
    o.pc = FFC_PC_GAMG; o.nv = 2;
    assert_int_equal(ffc_full_set_iterative(f, &o), FFC_ERR_NULL);
    const double bad[6] = {0, 0, 0, 1, NAN, 0};
    o.xyz = bad;
    assert_int_equal(ffc_full_set_iterative(f, &o), FFC_ERR_NONFINITE);
    assert_int_equal(ffc_full_set_iterative(NULL, &o), FFC_ERR_NULL);
    /* on = 0: back to UMFPACK, the same answer as before */
    o.on = 0;
    assert_int_equal(ffc_full_set_iterative(f, &o), FFC_OK);
    assert_int_equal(ffc_full_solve(f, PB_N, sys.nt, sys.Ti, sys.Tj, sys.Tv, 0, sys.b, x, &err), FFC_OK);
    assert_true(pb_diff(x, x0) <= 1e-13);
    ffc_full_free(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_same_solution), cmocka_unit_test(test_rigid_modes), cmocka_unit_test(test_dirichlet_exact), cmocka_unit_test(test_patterns), cmocka_unit_test(test_block),
        cmocka_unit_test(test_reasons),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
