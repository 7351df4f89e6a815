/* ffc_scene_out.c: a scene's statistics, points, multipliers, sizes, penalty, free motions, volume, mask. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ffc.h"
#include "ffc_bulk.h"
#include "ffc_internal.h"
#include "ffc_scene_state.h"

/* Statistics by name: how each one reads a pair's ffc_stats (get) or, for
 * node-to-surface pairs only, its ffc_nts_stats (nget; zero for other
 * pairs), and how the pairs combine (sum or maximum). */
typedef struct {
    const char *name;
    int sum;           /* 1: summed over pairs, 0: largest */
    double (*get)(const ffc_stats *st);
    double (*nget)(const ffc_nts_stats *st);
} stat_entry;

#define FFC__STAT(fn, expr) static double fn(const ffc_stats *st) { return (expr); }
FFC__STAT(st_linked, (double)st->linked)
FFC__STAT(st_active, (double)st->active)
FFC__STAT(st_max_pen, st->max_pen)
FFC__STAT(st_max_pen_node, st->max_pen_node)
FFC__STAT(st_max_dlam, st->max_dlam)
FFC__STAT(st_max_tn, st->max_tn)
FFC__STAT(st_fx, st->force[0])
FFC__STAT(st_fy, st->force[1])
FFC__STAT(st_fz, st->force[2])
FFC__STAT(st_stick, (double)st->stick)
FFC__STAT(st_slip, (double)st->slip)
FFC__STAT(st_max_dlam_t, st->max_dlam_t)
FFC__STAT(st_max_tt, st->max_tt)
FFC__STAT(st_ftx, st->force_t[0])
FFC__STAT(st_fty, st->force_t[1])
FFC__STAT(st_ftz, st->force_t[2])
FFC__STAT(st_dissipation, st->dissipation)
FFC__STAT(st_max_slip, st->max_slip)
#undef FFC__STAT
#define FFC__STAT(fn, expr) static double fn(const ffc_nts_stats *st) { return (expr); }
FFC__STAT(nst_changes, (double)st->changes)
FFC__STAT(nst_chatter, (double)st->chatter)
FFC__STAT(nst_released, (double)st->released)
FFC__STAT(nst_locked, (double)st->locked)
FFC__STAT(nst_gap_err, st->max_gap_err)
FFC__STAT(nst_slide_res, st->max_slide_res)
#undef FFC__STAT

static const stat_entry stat_table[] = {
    {"linked", 1, st_linked, NULL},          {"active", 1, st_active, NULL},
    {"maxPen", 0, st_max_pen, NULL},         {"maxPenNode", 0, st_max_pen_node, NULL},
    {"maxDlam", 0, st_max_dlam, NULL},       {"maxTn", 0, st_max_tn, NULL},
    {"Fx", 1, st_fx, NULL},                  {"Fy", 1, st_fy, NULL},
    {"Fz", 1, st_fz, NULL},                  {"stick", 1, st_stick, NULL},
    {"slip", 1, st_slip, NULL},              {"maxDlamT", 0, st_max_dlam_t, NULL},
    {"maxTt", 0, st_max_tt, NULL},           {"Ftx", 1, st_ftx, NULL},
    {"Fty", 1, st_fty, NULL},                {"Ftz", 1, st_ftz, NULL},
    {"dissipation", 1, st_dissipation, NULL}, {"maxSlip", 0, st_max_slip, NULL},
    {"changes", 1, NULL, nst_changes},       {"chatter", 1, NULL, nst_chatter},
    {"released", 1, NULL, nst_released},     {"locked", 1, NULL, nst_locked},
    {"gapErr", 0, NULL, nst_gap_err},        {"slideRes", 0, NULL, nst_slide_res},
};
#define FFC__NSTATS ((int)(sizeof stat_table / sizeof stat_table[0]))

const char *ffc_scene_stat_name(int i)
{
    return i >= 0 && i < FFC__NSTATS ? stat_table[i].name : NULL;
}

int ffc_scene_stat(const ffc_scene *s, int pair, const char *name, int step, double *value)
{
    if (!s || !name || !value) return FFC_ERR_NULL;
    if (pair < -1 || pair >= s->np) return FFC_ERR_INDEX;
    for (int i = 0; i < FFC__NSTATS; i++) {
        const stat_entry *e = &stat_table[i];
        if (strcmp(name, e->name)) continue;
        double r = 0.0;
        for (int k = 0; k < s->np; k++) {
            const scene_pair *p = &s->p[k];
            if ((pair >= 0 && k != pair) || (e->nget && p->o.method != FFC_METHOD_NTS)) continue;
            const double a = e->nget ? e->nget(step ? &p->nst_step : &p->nst) : e->get(step ? &p->st_step : &p->st);
            r = e->sum ? r + a : (a > r ? a : r);
        }
        *value = r;
        return FFC_OK;
    }
    return FFC_ERR_LABEL;
}

long ffc_scene_nlinks(const ffc_scene *s, int pair)
{
    if (!s) return FFC_ERR_NULL;
    if (pair < -1 || pair >= s->np) return FFC_ERR_INDEX;
    long n = 0;
    for (int k = 0; k < s->np; k++)
        if (pair < 0 || k == pair) n += s->p[k].o.method == FFC_METHOD_NTS ? s->p[k].nn : s->p[k].nl;
    return n;
}

/* the rows of pair p's output: its nodes (node-to-surface: every slave
 * node; mortar, or a nodal pair asked for nodes: the facets' vertices) or
 * its links; FFC_ERR_VALUE: nodes asked of pointwise multipliers */
static long pair_rows(const scene_pair *p, int nodes)
{
    if (p->o.method == FFC_METHOD_NTS) return p->nn;
    if (p->o.method == FFC_METHOD_MORTAR) return p->nsn;
    if (nodes) return p->o.nodal ? p->nsn : FFC_ERR_VALUE;
    return p->nl;
}

long ffc_scene_npoints(const ffc_scene *s, int pair, int nodes)
{
    if (!s) return FFC_ERR_NULL;
    if (pair < -1 || pair >= s->np) return FFC_ERR_INDEX;
    long n = 0;
    for (int k = 0; k < s->np; k++)
        if (pair < 0 || k == pair) {
            long r = pair_rows(&s->p[k], nodes);
            if (r < 0) return r;
            n += r;
        }
    return n;
}

/* Pair p's rows P[nr] at the committed state (u = the last commit's):
 * read again there, where no slip has happened since, each traction
 * passes the stick test (those that slid sit on the Coulomb cone); each
 * pressed row takes instead the state the step's last augmentation found
 * (fst0) wherever that found it pressed. Node rows (nodes = 1) are the
 * slave vertices in ascending order, as ffc_points_nodes writes them;
 * link rows take their nearest pressed corner's (nodal law, as
 * ffc_points does) or their link's. */
static int committed_states(const ffc_scene *s, const scene_pair *p, int node_rows, long nr, double P[])
{
    const int nper = s->nper;
    if (node_rows) {
        char *slave = calloc((size_t)s->nv, 1);   /* (a slave vertex: a row of ffc_points_nodes) */
        if (!slave) return FFC_ERR_MEMORY;
        for (long k = 0; k < p->nfs * nper; k++)
            if (k % nper < 3) slave[p->Fs[k]] = 1;
        long r = 0;
        for (long v = 0; v < s->nv && r < nr; v++) {
            if (!slave[v]) continue;
            double *st = &P[r++ * FFC_POINT_COLS + FFC_PT_STATE];
            if (*st != FFC_FRIC_OPEN && p->fst0[v] != FFC_FRIC_OPEN) *st = p->fst0[v];
        }
        free(slave);
        return FFC_OK;
    }
    for (long k = 0; k < nr; k++) {
        double *st = &P[k * FFC_POINT_COLS + FFC_PT_STATE];
        if (*st == FFC_FRIC_OPEN) continue;
        int found;
        if (p->o.nodal) {
            int corner[3];
            for (int a = 0; a < 3; a++) corner[a] = p->fst0[p->Fs[p->links[k].sf * nper + a]];
            const int c = ffc__nearest_corner(&p->links[k], corner);
            found = c < 0 ? FFC_FRIC_OPEN : corner[c];
        } else
            found = p->fst0[k];
        if (found != FFC_FRIC_OPEN) *st = found;
    }
    return FFC_OK;
}

int ffc_scene_points(const ffc_scene *s, const double u[], int pair, int nodes, long cap, double P[], long *n,
                     long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (!s || !u || !P || !n) return FFC_ERR_NULL;
    const long need = ffc_scene_npoints(s, pair, nodes);
    if (need < 0) return (int)need;
    *n = need;
    if (cap < need) return FFC_ERR_CAPACITY;
    long row = 0;
    for (int k = 0; k < s->np; k++) {
        if (pair >= 0 && k != pair) continue;
        const scene_pair *p = &s->p[k];
        if (p->o.method == FFC_METHOD_NTS) {
            int st = ffc_nts_points(s->nv, s->X, u, p->nn, p->nodes, P + row * FFC_POINT_COLS, bad);
            if (st < 0) return st;
            row += p->nn;
            continue;
        }
        const pair_call c = ffc__pair_view(s, p, u, FFC_TANGENT_NONE);
        const int node_rows = p->o.method == FFC_METHOD_MORTAR || nodes;
        const long nr = node_rows ? p->nsn : p->nl;
        int st;
        if (node_rows) {
            long got;
            st = ffc_points_nodes(&c.fx, &c.v, p->o.method == FFC_METHOD_MORTAR ? 0 : ffc__pair_qdeg(p), p->nl,
                                  p->links, p->lam, p->lam_t, &c.law, p->nsn, P + row * FFC_POINT_COLS, &got, bad);
        } else
            st = ffc_points(&c.fx, &c.v, ffc__pair_qdeg(p), p->nl, p->links, p->lam, p->lam_t, &c.law,
                            P + row * FFC_POINT_COLS, bad);
        if (st) return st;
        /* (fst0 is all open where the pair has no friction or no step has
         * been augmented: it changes no row) */
        if (!memcmp(u, s->u_prev, 3 * (size_t)s->nv * sizeof *u) &&
            (st = committed_states(s, p, node_rows, nr, P + row * FFC_POINT_COLS)))
            return st;
        row += nr;
    }
    return FFC_OK;
}

int ffc_scene_multipliers(const ffc_scene *s, int pair, long cap, double lam[], double lam_t[], long *n)
{
    if (!s || !n) return FFC_ERR_NULL;
    if (pair < 0 || pair >= s->np) return FFC_ERR_INDEX;
    const scene_pair *p = &s->p[pair];
    *n = p->nlam;
    if (cap < p->nlam) return FFC_ERR_CAPACITY;
    if (lam) memcpy(lam, p->lam, p->nlam * sizeof *lam);
    if (lam_t) memcpy(lam_t, p->lam_t, 3 * p->nlam * sizeof *lam_t);
    return FFC_OK;
}

int ffc_scene_check_volume(const ffc_scene *s, const double u[], long *bad)
{
    if (!s || !u) return FFC_ERR_NULL;
    if (!s->nt) return FFC_OK;
    long dummy;
    return ffc__volume_check_ref(s->nt, s->T, s->X, s->v0, u, bad ? bad : &dummy);
}

long ffc_scene_surface_mask(const ffc_scene *s, long n, double mask[])
{
    if (!s || !mask) return FFC_ERR_NULL;
    if (n != 3 * s->nv) return FFC_ERR_SIZE;
    for (long i = 0; i < n; i++) mask[i] = 0.0;
    long count = 0;
    for (int k = 0; k < s->np; k++) {
        const scene_pair *p = &s->p[k];
        for (int side = 0; side < 2; side++) {
            const long nf = side ? p->nfm : p->nfs, *F = side ? p->Fm : p->Fs;
            for (long a = 0; a < nf * s->nper; a++) {
                double *m = mask + 3 * F[a];
                if (m[0] == 0.0) count++;
                m[0] = m[1] = m[2] = 1.0;
            }
        }
    }
    return count;
}

/* (ffc_scene_state.h) */
double ffc__mean_size(int nper, long nf, const long F[], const double X[])
{
    double h = 0.0;
    for (long f = 0; f < nf; f++) {
        double l2 = 0.0;
        for (int a = 0; a < 3; a++) {
            const double *p = X + 3 * F[nper * f + a], *q = X + 3 * F[nper * f + (a + 1) % 3];
            const double d = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]);
            if (d > l2) l2 = d;
        }
        h += sqrt(l2);
    }
    return nf ? h / nf : 0.0;
}

int ffc_scene_facet_size(const ffc_scene *s, int pair, double *h)
{
    if (!s || !h) return FFC_ERR_NULL;
    if (pair < -1 || pair >= s->np) return FFC_ERR_INDEX;
    if (s->np == 0) return FFC_ERR_EMPTY;
    double r = INFINITY;
    for (int k = 0; k < s->np; k++) {
        if (pair >= 0 && k != pair) continue;
        const scene_pair *p = &s->p[k];
        const double hs = ffc__mean_size(s->nper, p->nfs, p->Fs, s->X),
                     hm = p->obst ? INFINITY : ffc__mean_size(s->nper, p->nfm, p->Fm, s->X);
        if (hs < r) r = hs;
        if (hm < r) r = hm;
    }
    *h = r;
    return FFC_OK;
}

double ffc_plane_modulus(double lame1, double lame2)
{
    return 4.0 * lame2 * (lame1 + lame2) / (lame1 + 2.0 * lame2);
}

/* mean of E'_f / h_f over nf facets: the stiffness of one element layer
 * under the surface (force/length^3) */
static int side_stiffness(int nper, long nf, const long F[], const double X[], const double Ep[], double *k)
{
    double sum = 0.0;
    for (long f = 0; f < nf; f++) {
        const double h = ffc__mean_size(nper, 1, F + nper * f, X);
        if (!(Ep[f] > 0) || !isfinite(Ep[f])) return FFC_ERR_VALUE;
        if (!(h > 0)) return FFC_ERR_DEGENERATE;
        sum += Ep[f] / h;
    }
    *k = sum / nf;
    return FFC_OK;
}

int ffc_scene_auto_penalty(const ffc_scene *s, int pair, const double Ep_s[], const double Ep_m[], double *eps)
{
    if (!s || !Ep_s || !eps) return FFC_ERR_NULL;
    if (pair < 0 || pair >= s->np) return FFC_ERR_INDEX;
    const scene_pair *p = &s->p[pair];
    if (!Ep_m && !p->obst) return FFC_ERR_NULL;
    double ks, km = INFINITY;   /* (a rigid obstacle: no compliance on its side) */
    int st = side_stiffness(s->nper, p->nfs, p->Fs, s->X, Ep_s, &ks);
    if (!st && !p->obst) st = side_stiffness(s->nper, p->nfm, p->Fm, s->X, Ep_m, &km);
    if (st) return st;
    *eps = 200.0 / (1.0 / ks + 1.0 / km);
    return FFC_OK;
}

int ffc_scene_free_motions(const ffc_scene *s, const double u[], long cap, ffc_motion out[], long *n)
{
    if (!s || !n) return FFC_ERR_NULL;
    if (s->nt < 1) return FFC_ERR_EMPTY;
    return ffc_rigid_free(s->nv, s->X, s->nt, s->T, s->fixed, u, cap, out, n);
}

long ffc_scene_nfacets(const ffc_scene *s, int pair, int master)
{
    if (!s) return FFC_ERR_NULL;
    if (pair < 0 || pair >= s->np) return FFC_ERR_INDEX;
    return master ? s->p[pair].nfm : s->p[pair].nfs;
}
