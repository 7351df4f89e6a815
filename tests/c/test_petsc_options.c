/* test_petsc_options.c: an option PETSc refuses (from PETSC_OPTIONS, read when PETSc starts) is an error naming it. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>

#include "petsc_test.h"

static pb_system sys;

/* PETSC_OPTIONS = "-ksp_type no_such_solver": the set-up fails with
 * FFC_ERR_VALUE (a caller's error, not a solve that stopped short: the
 * driver would cut the step and blame the Krylov budget), the message
 * naming PETSC_OPTIONS and PETSc's own words */
static void test_refused_option(void **state)
{
    (void)state;
    static double x[PB_N];
    ffc_full *f = NULL;
    ffc_error err = {0};
    assert_int_equal(ffc_full_create(&f), FFC_OK);
    const ffc_iterative o = {1, 0, 0, FFC_PC_GAMG, 1e-8, 100, 0, NULL};
    if (!ffc_has_petsc()) {
        assert_int_equal(ffc_full_set_iterative(f, &o), FFC_ERR_UNAVAILABLE);
        ffc_full_free(f);
        return;
    }
    assert_int_equal(ffc_full_set_iterative(f, &o), FFC_OK);
    pb_make(&sys);
    assert_int_equal(ffc_full_solve(f, PB_N, sys.nt, sys.Ti, sys.Tj, sys.Tv, 0, sys.b, x, &err), FFC_ERR_VALUE);
    printf("  %s\n", err.msg);
    assert_int_equal(err.status, FFC_ERR_VALUE);
    assert_non_null(strstr(err.msg, "PETSC_OPTIONS"));
    assert_non_null(strstr(err.msg, "no_such_solver"));
    ffc_full_free(f);
}

int main(void)
{
    /* (before PETSc starts: the engine starts it at its first use) */
    setenv("PETSC_OPTIONS", "-ksp_type no_such_solver", 1);
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_refused_option)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
