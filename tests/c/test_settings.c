/* test_settings.c: the scene driver's settings: their defaults, the
 * values a setting takes and refuses (each refusal one line naming the
 * setting and the value), words; the bulk law a scene declares. */
#include <stdio.h>

#include "ffc_test.h"

static void test_defaults_and_values(void **state)
{
    (void)state;
    ffc_settings s;
    ffc_settings_defaults(&s);
    double v = 0;
    assert_int_equal(ffc_settings_get(&s, "maxNewton", &v), FFC_OK);
    assert_close(v, 25, 0);
    assert_int_equal(ffc_settings_get(&s, "rtol", &v), FFC_OK);
    assert_close(v, 1e-9, 0);
    char w[32];
    assert_int_equal(ffc_settings_word(&s, "solver", w, sizeof w), FFC_OK);
    assert_string_equal(w, "auto");
    assert_int_equal(ffc_settings_word(&s, "mass", w, 5), FFC_ERR_CAPACITY);
    ffc_error e;
    assert_int_equal(ffc_settings_set(&s, "maxNewton", 40, &e), FFC_OK);
    assert_int_equal(ffc_settings_get(&s, "maxNewton", &v), FFC_OK);
    assert_close(v, 40, 0);
    assert_int_equal(ffc_settings_set_word(&s, "solver", "UMFPACK", &e), FFC_OK);
    assert_int_equal(ffc_settings_word(&s, "solver", w, sizeof w), FFC_OK);
    assert_string_equal(w, "UMFPACK");
    /* refusals, named */
    assert_int_equal(ffc_settings_set(&s, "nsteps", 0, &e), FFC_ERR_VALUE);
    assert_string_equal(e.msg, "'nsteps' = 0 is outside [1, 1e+09]");
    assert_int_equal(ffc_settings_set(&s, "lsTol", 1, &e), FFC_ERR_VALUE);
    assert_string_equal(e.msg, "'lsTol' = 1 is outside (0, 1)");
    assert_int_equal(ffc_settings_set(&s, "maxCuts", 2.5, &e), FFC_ERR_VALUE);
    assert_string_equal(e.msg, "'maxCuts' = 2.5 is not a whole number");
    assert_int_equal(ffc_settings_set(&s, "rtol", NAN, &e), FFC_ERR_VALUE);
    assert_int_equal(ffc_settings_set(&s, "maxNewtn", 3, &e), FFC_ERR_VALUE);
    assert_string_equal(e.msg, "'maxNewtn' is not a setting");
    assert_int_equal(ffc_settings_set_word(&s, "mass", "lumped", &e), FFC_ERR_VALUE);
    assert_string_equal(e.msg, "'mass' = \"lumped\" is not one of: redistributed consistent");
    assert_int_equal(ffc_settings_set(&s, "mass", 1, &e), FFC_ERR_VALUE);
    assert_int_equal(ffc_settings_set_word(&s, "rtol", "small", &e), FFC_ERR_VALUE);
    /* a refused value leaves the one before */
    assert_int_equal(ffc_settings_get(&s, "maxNewton", &v), FFC_OK);
    assert_close(v, 40, 0);
    /* the table: every name once, defaults within their own range */
    for (int i = 0; i < ffc_settings_count(); i++) {
        const ffc_setting *t = ffc_setting_at(i);
        assert_non_null(t);
        assert_int_equal(ffc_setting_find(t->name), i);
        ffc_settings d;
        ffc_settings_defaults(&d);
        if (t->type != FFC_SET_WORD) assert_int_equal(ffc_settings_set(&d, t->name, t->def, &e), FFC_OK);
    }
    assert_true(ffc_settings_count() <= FFC_NSETTINGS);
    assert_null(ffc_setting_at(ffc_settings_count()));
}

static void test_bulk_law(void **state)
{
    (void)state;
    const double X[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const long T[4] = {0, 1, 2, 3};
    const ffc_effects fx = {0, 0, 0};
    ffc_scene *s = NULL;
    assert_int_equal(ffc_scene_create(3, 4, X, 1, T, &fx, &s), FFC_OK);
    ffc_bulk_law l;
    assert_int_equal(ffc_scene_law(s, &l), FFC_OK);
    assert_int_equal(l.kind, FFC_BULK_LINEAR);
    assert_true(l.linear && l.symmetric && !l.finite);
    ffc_bulk_law nh = ffc_bulk_law_of(FFC_BULK_NEOHOOKEAN);
    assert_int_equal(ffc_scene_set_law(s, &nh), FFC_OK);
    ffc_effects f2;
    assert_int_equal(ffc_scene_effects(s, &f2), FFC_OK);
    assert_int_equal(f2.finite_def, 1);
    nh.linear = 1;   /* a built-in law declared otherwise */
    assert_int_equal(ffc_scene_set_law(s, &nh), FFC_ERR_VALUE);
    ffc_bulk_law u = {FFC_BULK_USER, 1, 0, 0};   /* the user's: linear, not symmetric */
    assert_int_equal(ffc_scene_set_law(s, &u), FFC_OK);
    assert_int_equal(ffc_scene_effects(s, &f2), FFC_OK);
    assert_int_equal(f2.finite_def, 0);
    u.finite = 1;   /* linear and finite: no */
    assert_int_equal(ffc_scene_set_law(s, &u), FFC_ERR_VALUE);
    assert_non_null(ffc_scene_settings(s));
    ffc_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_defaults_and_values), cmocka_unit_test(test_bulk_law)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
