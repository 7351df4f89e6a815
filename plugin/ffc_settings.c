/* ffc_settings.c: the scene driver's settings, named and validated (their
 * table: name, type, default, admissible values, meaning). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "ffc.h"

#define BIG 1e9
#define INF HUGE_VAL

/* open: bit 1, lo excluded; bit 2, hi excluded */
static const ffc_setting table[] = {
    {"nsteps", FFC_SET_INT, 1, 1, BIG, 0, NULL, "load (or time) steps per solveScene()"},
    {"maxNewton", FFC_SET_INT, 25, 1, BIG, 0, NULL, "Newton iterations per augmentation"},
    {"maxNewtonCondensed", FFC_SET_INT, 60, 1, BIG, 0, NULL,
     "iterations of the condensed Newton (the factored path); where it stops short, the full-system Newton goes "
     "on for maxNewton more"},
    {"maxUzawa", FFC_SET_INT, 30, 1, BIG, 0, NULL, "augmentations per load step"},
    {"uzawaEta", FFC_SET_REAL, 0.1, 0, 1, 2, NULL,
     "full-system Newton after an augmentation: done once |r| <= uzawaEta x its residual there (0: to rtol every "
     "time; the step's last augmentation is always to rtol)"},
    {"maxLineSearch", FFC_SET_INT, 8, 0, BIG, 0, NULL, "line-search evaluations per phase of a Newton iteration (0: full steps)"},
    {"lsTol", FFC_SET_REAL, 0.5, 0, 1, 3, NULL, "line search: a step is taken once |r(u + a du) . du| <= lsTol |r(u) . du|"},
    {"maxCuts", FFC_SET_INT, 6, 0, BIG, 0, NULL, "step bisections in a row before a solve gives up"},
    {"maxSteps", FFC_SET_INT, 200, 1, BIG, 0, NULL, "steps (converged or cut) per solveScene() before it gives up"},
    {"rtol", FFC_SET_REAL, 1e-9, 0, 1, 3, NULL, "Newton: |r| <= rtol x the force scale, on the free dofs"},
    {"pentol", FFC_SET_REAL, 1e-4, 0, INF, 1, NULL, "augmentations: largest weighted nodal penetration <= pentol x h"},
    {"ltol", FFC_SET_REAL, 1e-4, 0, INF, 1, NULL, "augmentations: largest multiplier change <= ltol x largest pressure"},
    {"epsNGrowMax", FFC_SET_REAL, 10, 1, INF, 0, NULL,
     "a pair's epsN is raised x10 while its multipliers creep, up to this many times its first penalty (1: never)"},
    {"epsTGrowMax", FFC_SET_REAL, 100, 1, INF, 0, NULL,
     "a pair's epsT is raised x10 while its tangential multipliers creep, up to this many times its epsN, for the "
     "rest of the load step (1: never)"},
    {"epsCap", FFC_SET_REAL, 100, 0, INF, 1, NULL, "a pair's epsN starts at most epsCap x its automatic penalty"},
    {"epsGrow", FFC_SET_INT, 1, 0, 1, 0, NULL,
     "1: a pair's epsN is raised x10 when an augmentation cuts the penetration by less than 4x"},
    {"freezeSearch", FFC_SET_INT, 1, 0, 1, 0, NULL,
     "1: a step keeps its links for the rest of it when the re-search makes the augmentations cycle"},
    {"predictor", FFC_SET_INT, 1, 0, 1, 0, NULL, "1: a load step starts from the extrapolated last increment"},
    {"verbose", FFC_SET_INT, 1, 0, 3, 0, NULL, "0: silent, 1: a line per step, 2: per Newton iteration, 3: more"},
    {"tgv", FFC_SET_REAL, 1e30, 0, INF, 1, NULL, "FreeFEM's tgv: the Dirichlet rows of the bulk tangent"},
    {"tangent", FFC_SET_WORD, 0, 0, 0, 0, "consistent material",
     "the contact tangent of Newton (material: no geometric terms, linear convergence)"},
    {"condensedTangent", FFC_SET_WORD, 0, 0, 0, 0, "auto ranked consistent material",
     "the condensed Newton's tangent (auto: ranked when every pair is nodal and frictionless, else consistent)"},
    {"solver", FFC_SET_WORD, 0, 0, 0, 0, "auto factored UMFPACK iterative",
     "the linear solves (auto: factored for a linear symmetric bulk, else UMFPACK; iterative: PETSc's Krylov "
     "solvers on the full system)"},
    {"preconditioner", FFC_SET_WORD, 0, 0, 0, 0, "gamg hypre mumps",
     "solver = iterative: GMRES preconditioned by GAMG with the rigid-body modes, by hypre's BoomerAMG, or a "
     "direct LU by MUMPS through PETSc"},
    {"krylovTol", FFC_SET_REAL, 1e-8, 0, 1, 3, NULL,
     "solver = iterative: true residual <= krylovTol x |b| (the Dirichlet rows' values exact)"},
    {"krylovMax", FFC_SET_INT, 1000, 1, 100000, 0, NULL, "solver = iterative: Krylov iterations per solve at most"},
    {"condensed", FFC_SET_INT, 1, 0, 1, 0, NULL,
     "1: the factored path runs each Newton loop in C on the contact dofs (the condensed Newton)"},
    {"maxContactDofs", FFC_SET_INT, 8000, 1, BIG, 0, NULL, "the factored path's limit on the contact dofs"},
    {"reuseKrylov", FFC_SET_INT, 8, 0, 1000, 0, NULL,
     "full systems: GMRES iterations at most on the last factorization (its preconditioner) before a new one "
     "(0: every system factorized)"},
    {"h", FFC_SET_REAL, 0, 0, INF, 0, NULL, "contact mesh size of the penetration test (0: ffcFacetSize(C))"},
    {"timeStep", FFC_SET_REAL, 0, 0, INF, 0, NULL,
     "dynamic scenes: the time one solveScene() covers, in nsteps time steps (0: quasi-static)"},
    {"newmarkGamma", FFC_SET_REAL, 0.5, 0.5, INF, 0, NULL, "Newmark's gamma (>= 1/2; 1/2: the trapezoidal rule)"},
    {"newmarkBeta", FFC_SET_REAL, 0.25, 0, INF, 1, NULL, "Newmark's beta (>= gamma / 2 for unconditional stability)"},
    {"mass", FFC_SET_WORD, 0, 0, 0, 0, "redistributed consistent",
     "the mass of a time step: redistributed off the contact surfaces, or consistent"},
    {"freeTurnWarn", FFC_SET_REAL, 0.01, 0, INF, 0, NULL,
     "warn of a body turned by more than this (radians) about an axis that contact alone holds (0: never)"},
    {"maxActive", FFC_SET_INT, 40, 1, BIG, 0, NULL, "node-to-surface: active-set iterations per step"},
    {"ntsSlideTol", FFC_SET_REAL, 1e-9, 0, INF, 1, NULL,
     "node-to-surface: Coulomb's law on sliding nodes to this fraction of the largest normal force"},
    {"elasticC", FFC_SET_INT, 1, 0, 1, 0, NULL,
     "1: the linear-elastic stiffness assembled in C; 0: by FreeFEM's varf"},
};

enum { NSET = sizeof table / sizeof *table };

int ffc_settings_count(void) { return NSET; }

const ffc_setting *ffc_setting_at(int i) { return i >= 0 && i < NSET ? &table[i] : NULL; }

int ffc_setting_find(const char *name)
{
    if (!name) return FFC_ERR_NULL;
    for (int i = 0; i < NSET; i++)
        if (!strcmp(table[i].name, name)) return i;
    return FFC_ERR_VALUE;
}

/* the position of word w in the list (-1: not in it) */
static int word_index(const char *words, const char *w)
{
    const size_t lw = strlen(w);
    int k = 0;
    for (const char *p = words; *p; k++) {
        const char *e = strchr(p, ' ');
        const size_t l = e ? (size_t)(e - p) : strlen(p);
        if (l == lw && !strncmp(p, w, l)) return k;
        p += l + (e ? 1 : 0);
    }
    return -1;
}

void ffc_settings_defaults(ffc_settings *s)
{
    for (int i = 0; i < NSET; i++) s->v[i] = table[i].def;
}

/* err = {FFC_ERR_VALUE, its message}; returns FFC_ERR_VALUE */
static int refuse(ffc_error *err, const char *msg)
{
    if (err) {
        *err = (ffc_error){FFC_ERR_VALUE, FFC_AT_NONE, -1, ""};
        snprintf(err->msg, sizeof err->msg, "%s", msg);
    }
    return FFC_ERR_VALUE;
}

/* the setting called name, of a word's type or a number's (word), or
 * NULL with err naming the cause */
static const ffc_setting *find_kind(const char *name, int word, ffc_error *err)
{
    char m[200];
    const int i = ffc_setting_find(name);
    if (i < 0) snprintf(m, sizeof m, "'%s' is not a setting", name);
    else if ((table[i].type == FFC_SET_WORD) == word) return &table[i];
    else if (word) snprintf(m, sizeof m, "'%s' takes a number, not a word", name);
    else snprintf(m, sizeof m, "'%s' takes one of the words: %s", name, table[i].words);
    refuse(err, m);
    return NULL;
}

int ffc_settings_set(ffc_settings *s, const char *name, double v, ffc_error *err)
{
    if (!s || !name) return FFC_ERR_NULL;
    char m[200];
    const ffc_setting *t = find_kind(name, 0, err);
    if (!t) return FFC_ERR_VALUE;
    const long i = t - table;
    const int lo_ok = (t->open & 1) ? v > t->lo : v >= t->lo, hi_ok = (t->open & 2) ? v < t->hi : v <= t->hi;
    if (!isfinite(v) || !lo_ok || !hi_ok) {
        snprintf(m, sizeof m, "'%s' = %g is outside %c%g, %g%c", name, v, (t->open & 1) ? '(' : '[', t->lo, t->hi,
                 (t->open & 2) ? ')' : ']');
        return refuse(err, m);
    }
    if (t->type == FFC_SET_INT && v != floor(v)) {
        snprintf(m, sizeof m, "'%s' = %g is not a whole number", name, v);
        return refuse(err, m);
    }
    s->v[i] = v;
    return FFC_OK;
}

int ffc_settings_set_word(ffc_settings *s, const char *name, const char *w, ffc_error *err)
{
    if (!s || !name || !w) return FFC_ERR_NULL;
    char m[200];
    const ffc_setting *t = find_kind(name, 1, err);
    if (!t) return FFC_ERR_VALUE;
    const long i = t - table;
    const int k = word_index(t->words, w);
    if (k < 0) {
        snprintf(m, sizeof m, "'%s' = \"%.60s\" is not one of: %s", name, w, t->words);
        return refuse(err, m);
    }
    s->v[i] = k;
    return FFC_OK;
}

int ffc_settings_get(const ffc_settings *s, const char *name, double *v)
{
    if (!s || !name || !v) return FFC_ERR_NULL;
    const int i = ffc_setting_find(name);
    if (i < 0) return FFC_ERR_VALUE;
    *v = s->v[i];
    return FFC_OK;
}

int ffc_settings_word(const ffc_settings *s, const char *name, char *out, long cap)
{
    if (!s || !name || !out) return FFC_ERR_NULL;
    const int i = ffc_setting_find(name);
    if (i < 0 || table[i].type != FFC_SET_WORD) return FFC_ERR_VALUE;
    const char *p = table[i].words;
    for (int k = 0; k < (int)s->v[i]; k++) p = strchr(p, ' ') + 1;
    const char *e = strchr(p, ' ');
    const long l = e ? (long)(e - p) : (long)strlen(p);
    if (l + 1 > cap) return FFC_ERR_CAPACITY;
    memcpy(out, p, (size_t)l);
    out[l] = '\0';
    return FFC_OK;
}
