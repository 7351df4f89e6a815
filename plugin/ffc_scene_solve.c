/* ffc_scene_solve.c: a scene's bulk (set, engine, solve), node-to-surface pairs, the condensed Newton. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ffc.h"
#include "ffc_bulk.h"
#include "ffc_internal.h"
#include "ffc_scene_state.h"

int ffc_scene_set_bulk(ffc_scene *s, long n, long nt, const long Ti[], const long Tj[], const double Tv[], long mmax,
                       long *bad)
{
    if (!s) return FFC_ERR_NULL;
    if (n != 3 * s->nv) return FFC_ERR_SIZE;
    ffc__bulk *b = NULL;
    int st = ffc__bulk_create(n, nt, Ti, Tj, Tv, mmax, &b, bad);
    if (st) return st;
    if ((s->par.engine == FFC_ENGINE_MUMPS && (st = ffc__bulk_set_mumps(b, s->par.comm))) ||
        (s->par.engine == FFC_ENGINE_REPLICATED && (st = ffc__bulk_set_replicated(b, s->par.comm)))) {
        ffc__bulk_free(b);
        return st;
    }
    ffc__bulk_free(s->bulk);
    s->bulk = b;
    return FFC_OK;
}

int ffc_scene_set_parallel(ffc_scene *s, const ffc_parallel *p)
{
    if (!s || !p) return FFC_ERR_NULL;
    if (p->engine != FFC_ENGINE_CHOLMOD && p->engine != FFC_ENGINE_MUMPS && p->engine != FFC_ENGINE_REPLICATED)
        return FFC_ERR_VALUE;
    if (p->engine != FFC_ENGINE_CHOLMOD && !ffc_has_mpi()) return FFC_ERR_UNAVAILABLE;
    s->par = *p;
    return FFC_OK;
}

int ffc_has_mpi(void)
{
#ifdef FFC_MPI
    return 1;
#else
    return 0;
#endif
}

int ffc_scene_solve(ffc_scene *s, long nt, const long Ti[], const long Tj[], const double Tv[], const double b[],
                    double x[], long *bad)
{
    if (!s) return FFC_ERR_NULL;
    if (!s->bulk) return FFC_ERR_EMPTY;
    return ffc__bulk_note(s->bulk, ffc__bulk_solve(s->bulk, nt, Ti, Tj, Tv, b, x, bad));
}

int ffc_scene_solve_error(const ffc_scene *s, ffc_error *err)
{
    if (!s || !err) return FFC_ERR_NULL;
    const ffc_error *e = ffc__bulk_error(s->bulk);
    if (e) *err = *e;
    else *err = (ffc_error){0, FFC_AT_NONE, -1, ""};
    return FFC_OK;
}

int ffc_scene_solve_info(const ffc_scene *s, ffc_solve_info *info)
{
    if (!s || !info) return FFC_ERR_NULL;
    ffc__bulk_info(s->bulk, info);
    return FFC_OK;
}

/* ------------------------------------------------ node-to-surface pairs */

/* The node-to-surface law of pair p (FFC_ERR_VALUE without a row scale). */
static int nts_law(const ffc_scene *s, const scene_pair *p, ffc_nts_law *law)
{
    law->nu_s = p->o.mu;
    law->nu_d = p->o.mu_d < 0 ? p->o.mu : p->o.mu_d;
    law->gtol = p->o.gtol > 0 ? p->o.gtol
                              : 1e-11 * fmin(ffc__mean_size(s->nper, p->nfs, p->Fs, s->X),
                                             ffc__mean_size(s->nper, p->nfm, p->Fm, s->X));
    law->ftol = p->o.ftol;
    law->max_flips = p->o.max_flips;
    law->scale = p->o.scale > 0 ? p->o.scale : ffc__bulk_kfree(s->bulk);
    return law->scale > 0 ? FFC_OK : FFC_ERR_VALUE;
}

/* The pair's ffc_stats from its node table: linked (nodes with a
 * partner), active (in contact), stick, slip, normal and tangential force
 * on the slave nodes, largest pressure and traction, dissipation |F_t . s|,
 * largest slip of a node in contact, largest penetration. */
static void nts_fill_stats(scene_pair *p)
{
    ffc_stats *st = &p->st;
    memset(st, 0, sizeof *st);
    for (long k = 0; k < p->nn; k++) {
        const ffc_nts_node *a = &p->nodes[k];
        if (a->mf >= 0) st->linked++;
        if (a->state == FFC_NTS_OPEN) continue;
        st->active++;
        if (a->state == FFC_NTS_STICK) st->stick++;
        else st->slip++;
        double ft[3], tt = 0.0, sl = 0.0, d = 0.0;
        for (int i = 0; i < 3; i++) {
            ft[i] = a->f[i] - a->fn * a->nr[i];
            st->force[i] += a->fn * a->nr[i];
            st->force_t[i] += ft[i];
            tt += ft[i] * ft[i];
            sl += a->slip[i] * a->slip[i];
            d += ft[i] * a->slip[i];
        }
        st->dissipation += fabs(d);
        if (a->area > 0) {
            st->max_tn = fmax(st->max_tn, a->fn / a->area);
            st->max_tt = fmax(st->max_tt, sqrt(tt) / a->area);
        }
        st->max_slip = fmax(st->max_slip, sqrt(sl));
    }
    st->max_pen = p->nst.max_pen;
    st->max_pen_node = p->nst.max_pen;
}

int ffc_scene_nts_step(ffc_scene *s)
{
    if (!s) return FFC_ERR_NULL;
    for (int k = 0; k < s->np; k++) {
        scene_pair *p = &s->p[k];
        for (long i = 0; i < p->nn; i++) {
            ffc_nts_node *a = &p->nodes[i];
            a->flips = 0;
            a->chatter = 0;
            a->mfprev = -1;   /* facets are searched again */
            a->frozen = 0;
            /* the step starts from the elastic predictor: no force of this
             * step yet (a sliding node's first rows hold it, and the update
             * sends it along the trial force) */
            memset(a->f, 0, sizeof a->f);
            a->fn = 0.0;
        }
    }
    return FFC_OK;
}

int ffc_scene_nts_rows(ffc_scene *s, const double u[], const double fixed[], long cap, long Bi[], long Bj[],
                       double Bv[], double Fv[], long ccap, double c[], long *ntrip, long *nrows, long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (!s || !u || !ntrip || !nrows) return FFC_ERR_NULL;
    if (cap < 0 || ccap < 0) return FFC_ERR_SIZE;
    if ((cap > 0 && (!Bi || !Bj || !Bv || !Fv)) || (ccap > 0 && !c)) return FFC_ERR_NULL;
    int st = ffc__scene_positions(s, u, bad);
    if (st) return st;
    const long n = 3 * s->nv;
    long nt = 0, nr = 0;
    int over = 0;
    for (int k = 0; k < s->np; k++) {
        scene_pair *p = &s->p[k];
        if (p->o.method != FFC_METHOD_NTS) continue;
        ffc_nts_law law;
        if ((st = nts_law(s, p, &law))) { *bad = k; return st; }
        const pair_call pc = ffc__pair_view(s, p, u, FFC_TANGENT_NONE);
        st = ffc_nts_locate(&pc.v, &law, &p->o.search, !p->located, p->nn, p->nodes);
        if (st) { *bad = k; return st; }
        p->located = 1;
        long t = 0, r = 0;
        const int room = !over && cap > nt, croom = !over && ccap > nr;
        st = ffc_nts_rows(&pc.v, &law, fixed, p->nn, p->nodes, room ? cap - nt : 0, room ? Bi + nt : NULL,
                          room ? Bj + nt : NULL, room ? Bv + nt : NULL, room ? Fv + nt : NULL, croom ? ccap - nr : 0,
                          croom ? c + nr : NULL, &t, &r);
        if (st == FFC_ERR_CAPACITY) over = 1;
        else if (st) { *bad = k; return st; }
        if (!over) /* this pair's rows follow the others' */
            for (long i = nt; i < nt + t; i++) {
                Bi[i] += nr;
                if (Bj[i] >= n) Bj[i] += nr;
            }
        p->row0 = nr;
        p->nr = r;
        nt += t;
        nr += r;
    }
    *ntrip = nt;
    *nrows = nr;
    return over ? FFC_ERR_CAPACITY : FFC_OK;
}

int ffc_scene_nts_solve(ffc_scene *s, const double u[], const double fixed[], const double rhs[], double x[],
                        long mcap, double m[], long *nrows, long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (!s || !u || !fixed || !rhs || !x || !nrows || (mcap > 0 && !m)) return FFC_ERR_NULL;
    if (mcap < 0) return FFC_ERR_SIZE;
    if (!s->bulk) return FFC_ERR_EMPTY;
    const long n = 3 * s->nv;
    for (long i = 0; i < n; i++)
        if (!isfinite(rhs[i])) { *bad = i; return FFC_ERR_NONFINITE; }
    long nt = 0, nr = 0;
    int st = ffc_scene_nts_rows(s, u, fixed, 0, NULL, NULL, NULL, NULL, 0, NULL, &nt, &nr, bad);
    if (st && st != FFC_ERR_CAPACITY) return st;
    *nrows = nr;
    if (nr > mcap) return FFC_ERR_CAPACITY;
    long *Bi = malloc((size_t)(nt + 1) * sizeof(long)), *Bj = malloc((size_t)(nt + 1) * sizeof(long));
    double *Bv = malloc((size_t)(nt + 1) * sizeof(double)), *Fv = malloc((size_t)(nt + 1) * sizeof(double));
    double *c = malloc((size_t)(nr + 1) * sizeof(double));
    if (!Bi || !Bj || !Bv || !Fv || !c) st = FFC_ERR_MEMORY;
    else st = ffc_scene_nts_rows(s, u, fixed, nt, Bi, Bj, Bv, Fv, nr, c, &nt, &nr, bad);
    if (!st) st = ffc__bulk_note(s->bulk, ffc__bulk_saddle(s->bulk, nt, Bi, Bj, Bv, Fv, nr, c, rhs, x, m, bad));
    free(Bi); free(Bj); free(Bv); free(Fv); free(c);
    return st;
}

int ffc_scene_nts_update(ffc_scene *s, const double u[], long nrows, const double m[], long *changes, long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (!s || !u || !changes || (nrows > 0 && !m)) return FFC_ERR_NULL;
    int st = ffc__scene_positions(s, u, bad);
    if (st) return st;
    /* the rows of each pair, which must add up to nrows */
    long total = 0;
    for (int k = 0; k < s->np; k++)
        if (s->p[k].o.method == FFC_METHOD_NTS) total += s->p[k].nr;
    if (total != nrows) { *bad = total; return FFC_ERR_SIZE; }
    for (long i = 0; i < nrows; i++)
        if (!isfinite(m[i])) { *bad = i; return FFC_ERR_NONFINITE; }
    long ch = 0;
    for (int k = 0; k < s->np; k++) {
        scene_pair *p = &s->p[k];
        if (p->o.method != FFC_METHOD_NTS) continue;
        ffc_nts_law law;
        if ((st = nts_law(s, p, &law))) { *bad = k; return st; }
        const long r = p->nr, off = p->row0;
        const pair_call pc = ffc__pair_view(s, p, u, FFC_TANGENT_NONE);
        st = ffc_nts_locate(&pc.v, &law, &p->o.search, 0, p->nn, p->nodes);
        if (!st) st = ffc_nts_update(&law, r, m + off, p->nn, p->nodes, &p->nst);
        if (st) { *bad = k; return st; }
        ch += p->nst.changes;
        nts_fill_stats(p);
    }
    *changes = ch;
    return FFC_OK;
}

int ffc_scene_nts_force(const ffc_scene *s, double R[])
{
    if (!s || !R) return FFC_ERR_NULL;
    for (int k = 0; k < s->np; k++) {
        const scene_pair *p = &s->p[k];
        if (p->o.method != FFC_METHOD_NTS) continue;
        for (long i = 0; i < p->nn; i++) {
            const ffc_nts_node *a = &p->nodes[i];
            /* (an open node's force is released; at a converged update no
             * node changed state, so these are the forces that balanced the
             * last solve) */
            if (a->state == FFC_NTS_OPEN || a->mf < 0) continue;
            for (int j = 0; j < 3; j++) {
                R[3 * a->node + j] -= a->f[j];
                for (int c = 0; c < 3; c++) R[3 * p->Fm[3 * a->mf + c] + j] += a->L[c] * a->f[j];
            }
        }
    }
    return FFC_OK;
}

/* ------------------------------------------- condensed Newton (small strain) */

ffc_newton_opts ffc_newton_defaults(void)
{
    ffc_newton_opts o;
    o.max_iter = 25;
    o.max_ls = 8;
    o.ls_tol = 0.5;
    o.ftol = 0.0;
    o.frel = 0.0;
    o.tangent = FFC_TANGENT_CONSISTENT;
    o.max_dofs = 0;
    o.min_iter = 0;
    return o;
}

/* the contact evaluation the bulk's Newton calls: the scene's assembly,
 * with a dynamic scene's velocities following u (v = v0 + dvdu (u - u0)) */
typedef struct {
    ffc_scene *s;
    const double *u0;  /* [n] the displacement Newton starts from */
    const double *v0;  /* [n] the velocities there, or NULL (quasi-static) */
    const share_ctx *share; /* the ranks sharing out the links, or NULL */
    int shared;        /* evaluations that shared out some pair's links */
} newton_ctx;

static int newton_contact(void *ctx, const double u[], int tangent, double R[], long cap, long Ti[], long Tj[],
                          double Tv[], long *nt, double *fmag, double state[3], long *bad)
{
    newton_ctx *c = ctx;
    if (c->v0)
        for (long i = 0; i < 3 * c->s->nv; i++) c->s->v[i] = c->v0[i] + c->s->dvdu * (u[i] - c->u0[i]);
    int any = 0;
    const int st = ffc__scene_assemble(c->s, u, tangent, R, cap, Ti, Tj, Tv, nt, bad, c->share, &any);
    c->shared += any && st != FFC_ERR_CAPACITY;   /* (a retry with more room is the same evaluation) */
    const char *force[3] = {"Fx", "Fy", "Fz"}, *count[3] = {"active", "stick", "slip"};
    *fmag = 0.0;
    for (int i = 0; i < 3; i++) {
        double f = 0.0;
        ffc_scene_stat(c->s, -1, force[i], 0, &f);
        *fmag += fabs(f);
        state[i] = 0.0;
        ffc_scene_stat(c->s, -1, count[i], 0, &state[i]);
    }
    return st;
}

int ffc_scene_newton(ffc_scene *s, const double r[], double u[], const ffc_newton_opts *o, ffc_newton_info *info,
                     long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (!s || !r || !u || !o || !info) return FFC_ERR_NULL;
    memset(info, 0, sizeof *info);
    if (!s->bulk) return FFC_ERR_EMPTY;
    if (!ffc__penalties_set(s, bad)) return FFC_ERR_VALUE;
    for (int k = 0; k < s->np; k++)
        if (s->p[k].o.method == FFC_METHOD_NTS || (o->tangent == FFC_TANGENT_RANKED && !s->p[k].o.nodal)) {
            *bad = k;
            return FFC_ERR_VALUE;
        }
    const long n = 3 * s->nv;
    /* the rows: the dofs of every facet of the pairs (the contact
     * evaluation reads and loads no other); cand: those of every linked
     * point's slave and master facets (the shift of a singular K) */
    unsigned char *mark = calloc((size_t)n, 1);
    long *cand = malloc((size_t)n * sizeof(long)), *rows = malloc((size_t)n * sizeof(long));
    double *u0 = NULL, *v0 = NULL;
    if (s->fx.dynamic) {
        u0 = malloc((size_t)n * sizeof(double));
        v0 = malloc((size_t)n * sizeof(double));
    }
    int st = FFC_OK;
    if (!mark || !cand || !rows || (s->fx.dynamic && (!u0 || !v0))) st = FFC_ERR_MEMORY;
    long nc = 0, nr = 0;
    for (int k = 0; k < s->np && !st; k++) {
        const scene_pair *p = &s->p[k];
        for (long l = 0; l < p->nl; l++) {
            const ffc_link *L = &p->links[l];
            if (L->mf < 0) continue;
            for (int side = 0; side < (p->obst ? 1 : 2); side++) {
                const long *F = side ? p->Fm + L->mf * s->nper : p->Fs + L->sf * s->nper;
                for (int a = 0; a < s->nper; a++)
                    for (int c = 0; c < 3; c++) {
                        const long d = 3 * F[a] + c;
                        if (!mark[d]) { mark[d] = 1; cand[nc++] = d; }
                    }
            }
        }
    }
    for (int k = 0; k < s->np && !st; k++) {
        const scene_pair *p = &s->p[k];
        for (int side = 0; side < 2; side++) {
            const long nf = side ? p->nfm : p->nfs, *F = side ? p->Fm : p->Fs;
            for (long f = 0; f < nf * s->nper; f++)
                for (int c = 0; c < 3; c++) {
                    const long d = 3 * F[f] + c;
                    if (mark[d] != 2) { mark[d] = 2; rows[nr++] = d; }
                }
        }
    }
    if (!st) {
        if (v0) {
            memcpy(u0, u, (size_t)n * sizeof(double));
            memcpy(v0, s->v, (size_t)n * sizeof(double));
        }
        /* on several ranks (every rank holds the scene whole), each
         * evaluates its share of the links */
        share_ctx sh = {s->par.comm, 0, 1};
        if (s->par.engine != FFC_ENGINE_CHOLMOD) ffc__mpi_ranks(s->par.comm, &sh.rank, &sh.size);
        newton_ctx c = {s, u0, v0, sh.size > 1 && s->par.links ? &sh : NULL, 0};
        st = ffc__bulk_newton(s->bulk, nr, rows, nc, cand, newton_contact, &c, r, u, o, info, bad);
        info->evals_shared = c.shared;
        if (v0) /* the velocities of the displacement returned */
            for (long i = 0; i < n; i++) s->v[i] = v0[i] + s->dvdu * (st < 0 ? 0.0 : u[i] - u0[i]);
    }
    free(mark);
    free(cand);
    free(rows);
    free(u0);
    free(v0);
    return st;
}
