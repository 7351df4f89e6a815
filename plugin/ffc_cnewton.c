/* ffc_cnewton.c: Newton's method on the condensed contact problem (the
 * contact dofs C of a small-strain scene, the interior eliminated by the
 * compliance G), with the Newton loops' line search. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ffc_bulk_state.h"
#include "ffc_internal.h"

enum { REFRESH = 8 };      /* y = d0_C + G z and H z recomputed from z every this many iterations (between,
                              the steps G dz, H dz are added) */
enum { RANKED_SLOW = 2 };  /* ranked iterations that did not gain 10x on an unchanged active set before the
                              rest of a call takes the consistent tangent */

/* The first factorization: K alone; when K is singular (a body that only
 * contact holds), K + S shifted on the nodes the contact force reaches
 * (reach[nreach]), else on the linked points' facets (cand[nc]); see
 * factorize.  FFC_ERR_CAPACITY, no factor kept, when the shift would put
 * more than cap dofs in C.  The shifted dofs belong to C (their shift is
 * part of the condensed problem). */
static int first_factor(ffc__bulk *b, long nreach, const long reach[], long nc, const long cand[], long cap,
                        long *bad)
{
    int st = FFC_OK;
    if (!b->factored) {
        st = ffc__bulk_factorize(b, 0, NULL);
        for (int pass = 0; pass < 3 && st == FFC_ERR_SINGULAR; pass++) {
            long nset = 0;
            if (pass == 0) {   /* three nodes far apart in each body of the reach and the facets */
                long *sd = malloc((size_t)(nreach + nc + 1) * sizeof(long));
                if (!sd) return FFC_ERR_MEMORY;
                if (nreach) memcpy(sd, reach, (size_t)nreach * sizeof(long));
                if (nc) memcpy(sd + nreach, cand, (size_t)nc * sizeof(long));
                st = ffc__bulk_agree(b, ffc__bulk_spread_dofs(b, nreach + nc, sd, &nset));
                free(sd);
            } else
                st = pass == 2 ? ffc__bulk_free_dofs(b, nc, cand, 0, &nset, bad) : ffc__bulk_free_dofs(b, nreach, reach, 1, &nset, bad);
            if (st) return st;
            if (!nset) { st = FFC_ERR_SINGULAR; continue; }
            if (b->m + nset > cap) { *bad = b->m + nset; return FFC_ERR_CAPACITY; }
            st = ffc__bulk_factorize(b, nset, b->nd);
        }
        if (st) return st;
    }
    return ffc__bulk_shifted_into_c(b, cap, bad);
}

/* the free dofs outside C that the force in b->r or a triplet of the
 * tangent (b->ti, tj, tv)[nt] (free row and column; with ranked, the
 * FFC_TANGENT_RANKED form, its row: tj is a term) reaches, into
 * b->nd[*nnew]; FFC_ERR_INDEX (*bad = the dof) for one outside the rows */
static int reached(ffc__bulk *b, long nt, int ranked, long *nnew, long *bad)
{
    long *pos = b->pos, c = 0;
    int st = FFC_OK;
    for (long k = 0; k < b->m; k++) pos[b->dof[k]] = k;
#define REACH(i_)                                                                                                  \
    do {                                                                                                           \
        const long d_ = (i_);                                                                                      \
        if (b->big[d_] || pos[d_] != -1) break;                                                                    \
        if (b->rpos[d_] < 0) { *bad = d_; st = FFC_ERR_INDEX; break; }                                             \
        pos[d_] = -2;                                                                                              \
        b->nd[c++] = d_;                                                                                           \
    } while (0)
    for (long i = 0; i < b->n && !st; i++)
        if (b->r[i] != 0.0) REACH(i);
    for (long e = 0; e < nt && !st; e++)
        if (ranked) {
            if (b->tv[e] != 0.0) REACH(b->ti[e]);
        } else if (b->tv[e] != 0.0 && !b->big[b->ti[e]] && !b->big[b->tj[e]]) {
            REACH(b->ti[e]);
            if (!st) REACH(b->tj[e]);
        }
#undef REACH
    for (long k = 0; k < c; k++) pos[b->nd[k]] = -1;
    for (long k = 0; k < b->m; k++) pos[b->dof[k]] = -1;
    *nnew = st ? 0 : c;
    return st;
}

/* the contact force F (into b->r) and, with a tangent, its triplets
 * (b->ti, tj, tv)[*nt] at w; the triplet buffers grow as needed */
static int contact_eval(ffc__bulk *b, ffc__contact_fn fn, void *ctx, const double w[], int tangent, long *nt,
                        double *fmag, long *bad)
{
    long need = tangent && b->tcap == 0 ? 4096 : 0;
    for (int pass = 0; pass < 3; pass++) {
        if (need > b->tcap) {
            long *ti = realloc(b->ti, (size_t)need * sizeof(long));
            if (ti) b->ti = ti;
            long *tj = ti ? realloc(b->tj, (size_t)need * sizeof(long)) : NULL;
            if (tj) b->tj = tj;
            double *tv = tj ? realloc(b->tv, (size_t)need * sizeof(double)) : NULL;
            if (!tv) return FFC_ERR_MEMORY;
            b->tv = tv;
            b->tcap = need;
        }
        memset(b->r, 0, (size_t)b->n * sizeof(double));
        const double t0 = ffc__seconds();
        int st = fn(ctx, w, tangent, b->r, tangent ? b->tcap : 0, b->ti, b->tj, b->tv, nt, fmag, b->cstate, bad);
        if (b->t_eval) *b->t_eval += ffc__seconds() - t0;
        if (st != FFC_ERR_CAPACITY || !tangent) return st;
        need = *nt + *nt / 2 + 64;
    }
    return FFC_ERR_CAPACITY;
}

/* Fp = F_C - sh_C y from the force in b->r; FFC_ERR_INDEX (*bad = the
 * dof) when the force reaches a free dof outside C */
static int force_c(const ffc__bulk *b, const double y[], double Fp[], long *bad)
{
    for (long k = 0; k < b->m; k++) b->pos[b->dof[k]] = k;
    int st = FFC_OK;
    for (long i = 0; i < b->n && !st; i++)
        if (b->r[i] != 0.0 && !b->big[i] && b->pos[i] < 0) { *bad = i; st = FFC_ERR_INDEX; }
    for (long k = 0; k < b->m; k++) {
        const long d = b->dof[k];
        Fp[k] = b->r[d] - b->sh[d] * y[k];
        if (!isfinite(Fp[k])) { *bad = d; st = st ? st : FFC_ERR_NONFINITE; }
        b->pos[d] = -1;
    }
    return st;
}

/* the full step taken on the residual alone (rt[m]: rho there, the last
 * evaluation; rn: |rho| at the start, s0 its contact state): |rho| at
 * least halved and the contact state as it was, no kink of the law between */
static int full_step_taken(const ffc__bulk *b, long m, const double rt[], double rn, const double s0[3])
{
    return sqrt(ffc__dotn(m, rt, rt)) <= 0.5 * rn && b->cstate[0] == s0[0] && b->cstate[1] == s0[1] &&
           b->cstate[2] == s0[2];
}

/* Formulation (the closing solve kept).  A call ends at u' = u + d0 - x,
 * x = K'^-1 (-P_C^T z), and K d0 = b' = f - K u on the free rows, so the
 * next call's b'' = f - K u' = -P_C^T z when the load, the Dirichlet
 * values and K' are the same (an augmentation: only the multipliers
 * changed, and they are not in b'), and its d0 is x (with a shift S, a
 * body that only contact holds, b'' has S (d0 - x) more and is solved
 * afresh, unless S (d0 - x) is as small as below).  Taken when b''
 * (lifted) equals that right-hand side to REUSE_TOL of its largest entry
 * and to the force tolerance tol of the call (what differs is the
 * round-off of the residual f - K u' that the caller formed, and of the
 * two solves; the difference is left in the free rows' residual of the
 * returned state, below tol); every rank decides alike. */
#define REUSE_TOL 1e-10
static int same_rhs(const ffc__bulk *b, const double rhs[], double tol)
{
    int ok = b->prev;
    if (ok) {
        double e = 0.0, s = 0.0;
        for (long i = 0; i < b->n; i++) {
            const double d = fabs(rhs[i] - b->bprev[i]);
            if (!(d <= e)) e = d;   /* (a NaN stays: no reuse, and the solve reports it) */
            s = fmax(s, fabs(b->bprev[i]));
        }
        ok = s > 0.0 && e <= REUSE_TOL * s && e <= tol;
    }
    return ffc__bulk_all(b, ok);
}

/* keeps the closing solve K'^-1 rhs = x (nothing kept when short of memory) */
static void keep_closing(ffc__bulk *b, const double rhs[], const double x[])
{
    const size_t bytes = (size_t)b->n * sizeof(double);
    if (!b->bprev) b->bprev = malloc(bytes);
    if (!b->xprev) b->xprev = malloc(bytes);
    b->prev = b->bprev && b->xprev;
    if (!b->prev) return;
    memcpy(b->bprev, rhs, bytes);
    memcpy(b->xprev, x, bytes);
}

/* The state of one condensed Newton call.  C grows up to mm dofs.
 * m-vectors: y = d_C, z = G^-1 (y - d0_C) (the reaction that holds C at
 * y: the primary unknown; y = d0_C + G z advanced by the same steps and
 * recomputed from z every REFRESH iterations, so that the two drift apart
 * by round-off only), rho, dy, dz, gdz = G dz, Fp, rt, q, tt, ss, d0_C;
 * ap, ad; on the rows: hz = H z, hdz = H dz (the displacement of the rows
 * outside C: u + d0 + H z). */
typedef struct {
    ffc__bulk *b;
    ffc__contact_fn fn;
    void *ctx;
    const ffc_newton_opts *o;
    ffc_newton_info *info;
    long *bad;
    const double *u;           /* [n] the start */
    double *w, *d0, *rhs;      /* [n] (the bulk's work): the state evaluated, K^-1 b', a right-hand side */
    long cap;                  /* contact dofs C may hold */
    long m, nrb;               /* contact dofs now, rows R */
    int mi, nri, ldi;          /* the same as BLAS ints (G's leading dimension grows with C) */
    long nt, nnew;             /* the last evaluation's tangent triplets, dofs it reached outside C */
    double fm, fscale;         /* its force scale; the largest at an iteration's start */
    int restart;               /* 1: the iteration is taken again at the same state (C grew) */
    double *buf;
    long *ibuf;
    double *y, *z, *rho, *dy, *dz, *gdz, *Fp, *rt, *q, *tt, *ss, *d0c, *hz, *hdz;
    long *ap, *ad;
} cnewton;

/* y = d0_C + G z */
static void y_of_z(cnewton *c)
{
    const int one = 1;
    const double d1 = 1.0;
    memcpy(c->y, c->d0c, (size_t)c->m * sizeof(double));
    if (c->m) dgemv_("N", &c->mi, &c->mi, &d1, c->b->G, &c->ldi, c->z, &one, &d1, c->y, &one);
}

/* hz = H z */
static void h_z(cnewton *c)
{
    const int one = 1;
    const double d1 = 1.0, d0s = 0.0;
    if (c->m && c->nrb) dgemv_("N", &c->nri, &c->mi, &d1, c->b->H, &c->nri, c->z, &one, &d0s, c->hz, &one);
    else for (long k = 0; k < c->nrb; k++) c->hz[k] = 0.0;
}

/* w at z + a dz: the rows u + d0 + H (z + a dz), C's dofs u + yc */
static void w_at(cnewton *c, double a, const double yc[])
{
    const ffc__bulk *b = c->b;
    for (long k = 0; k < c->nrb; k++)
        c->w[b->rows[k]] = c->u[b->rows[k]] + c->d0[b->rows[k]] + c->hz[k] + a * c->hdz[k];
    for (long k = 0; k < c->m; k++) c->w[b->dof[k]] = c->u[b->dof[k]] + yc[k];
}

/* the dofs b->nd[nnew] join C at the state z: d0_C, z = 0 and y there */
static int join(cnewton *c)
{
    ffc__bulk *b = c->b;
    const long m0 = c->m;
    const int st = ffc__bulk_add_to_c(b, c->nnew, b->nd, c->cap, c->bad);
    if (st) return st;
    c->m = b->m;
    c->mi = (int)c->m;
    c->ldi = (int)b->ld;
    for (long k = m0; k < c->m; k++) {
        c->d0c[k] = c->d0[b->dof[k]];
        c->z[k] = 0.0;
        c->y[k] = c->d0c[k] + ffc__dotn(m0, b->G + k * b->ld, c->z); /* G symmetric: row k = column k */
    }
    c->info->grown += c->nnew;
    return FFC_OK;
}

/* the start: C held at u (y = 0), the rest equilibrated.  y = 0 exactly
 * (d0_C + G z is zero to round-off): the first evaluation sees u itself
 * on C, as a Newton step of the full system would (a point just touching
 * sits on the kink of the law, where round-off would pick the other side) */
static void start(cnewton *c)
{
    for (long k = 0; k < c->m; k++) {
        c->d0c[k] = c->d0[c->b->dof[k]];
        c->z[k] = -c->d0c[k];
        c->y[k] = 0.0;
    }
    ffc__bulk_g_inverse(c->b, c->z);
    h_z(c);
    w_at(c, 0.0, c->y);
}

/* rho at z + a dz into rt (its g is rt . gdz); a force that reaches a dof
 * outside C: it joins C and the iteration restarts */
static int trial(cnewton *c, double a)
{
    for (long k = 0; k < c->m; k++) c->rt[k] = c->y[k] + a * c->gdz[k];
    w_at(c, a, c->rt);
    int st = contact_eval(c->b, c->fn, c->ctx, c->w, FFC_TANGENT_NONE, &c->nt, &c->fm, c->bad);
    c->info->evals++;
    if (!st) st = reached(c->b, 0, 0, &c->nnew, c->bad);
    if (!st && c->nnew) {
        st = join(c);
        c->restart = 1;
    }
    if (!st && !c->restart) {
        st = force_c(c->b, c->rt, c->Fp, c->bad);
        for (long k = 0; k < c->m; k++) c->rt[k] = c->z[k] + a * c->dz[k] + c->Fp[k];
    }
    return st;
}

/* Up to the start: the rows R, the contact force at u (b' = -(r - F_c(u))
 * on free rows, -r on Dirichlet rows, into w; the dofs it reaches join
 * C), the first factorization, G's factor, d0 = K^-1 b' with the Dirichlet
 * values moved to the right-hand side (or the last call's closing solve,
 * when b' is its right-hand side), the work. */
static int setup(cnewton *c, long nr, const long rows[], long nc, const long cand[], const double r[])
{
    ffc__bulk *b = c->b;
    const ffc_newton_opts *o = c->o;
    const long n = b->n;
    int st = ffc__bulk_set_rows(b, nr, rows, c->bad);
    if (st) return st;
    st = contact_eval(b, c->fn, c->ctx, c->u, FFC_TANGENT_NONE, &c->nt, &c->fm, c->bad);
    c->info->evals++;
    if (!st) {
        for (long i = 0; i < n; i++) c->w[i] = b->big[i] ? -r[i] : b->r[i] - r[i];
        st = reached(b, 0, 0, &c->nnew, c->bad);
    }
    long *reach = NULL;
    if (!st && !b->factored) { /* (the force's dofs kept: ffc__bulk_free_dofs writes b->nd) */
        reach = malloc((size_t)(c->nnew + 1) * sizeof(long));
        if (!reach) st = FFC_ERR_MEMORY;
        else memcpy(reach, b->nd, (size_t)c->nnew * sizeof(long));
    }
    if (!st) st = first_factor(b, c->nnew, reach, nc, cand, c->cap, c->bad);
    free(reach);
    if (!st) st = reached(b, 0, 0, &c->nnew, c->bad);
    if (!st) st = ffc__bulk_add_to_c(b, c->nnew, b->nd, c->cap, c->bad);
    if (!st) st = ffc__bulk_factor_g(b);
    if (st) return st;
    ffc__bulk_lift(b, 0, NULL, NULL, NULL, c->w, c->rhs);
    if (same_rhs(b, c->rhs, fmax(o->ftol, o->frel * c->fm))) {
        memcpy(c->d0, b->xprev, (size_t)n * sizeof(double));
        b->info.reused++;
    } else
        st = ffc__bulk_backsolve(b, c->rhs, c->d0);
    if (st) return st;
    c->m = b->m;
    c->nrb = b->nr;
    const long m = c->m, nrb = c->nrb, cap = c->cap;
    const size_t mm = (size_t)(m + nrb < cap ? m + nrb : (cap > m ? cap : m)) + 1, mr = (size_t)nrb + 1;
    c->buf = malloc((12 * mm + 2 * mr) * sizeof(double));
    c->ibuf = malloc(2 * mm * sizeof(long));
    if (!c->buf || !c->ibuf) {
        free(c->buf); free(c->ibuf);
        c->buf = NULL;
        c->ibuf = NULL;
        return FFC_ERR_MEMORY;
    }
    c->y = c->buf; c->z = c->y + mm; c->rho = c->z + mm; c->dy = c->rho + mm; c->dz = c->dy + mm;
    c->gdz = c->dz + mm; c->Fp = c->gdz + mm; c->rt = c->Fp + mm; c->q = c->rt + mm; c->tt = c->q + mm;
    c->ss = c->tt + mm; c->d0c = c->ss + mm; c->hz = c->d0c + mm; c->hdz = c->hz + mr;
    c->ap = c->ibuf; c->ad = c->ibuf + mm;
    c->mi = (int)m;
    c->nri = (int)nrb;
    c->ldi = (int)b->ld;
    for (long i = 0; i < n; i++) c->w[i] = c->u[i] + (b->big[i] ? c->d0[i] : 0.0);
    for (long k = 0; k < nrb; k++) c->hdz[k] = 0.0;
    start(c);
    return FFC_OK;
}

/* The direction at this iteration (the consistent or ranked tangent of
 * the last evaluation) and gdz = G dz; with the consistent tangent and
 * g(0) = rho . G dz >= 0, first its full step, taken where it at least
 * halves |rho| and leaves the contact state as it was (*whole = 1; with
 * friction the tangent is not symmetric and g need not fall along a good
 * Newton step), else the material tangent's direction (the consistent
 * one is indefinite here).  *g0 = rho . G dz; hdz = H dz. */
static int step_direction(cnewton *c, int tmode, double rn, const double state0[3], long *na, int *whole,
                          double *g0)
{
    ffc__bulk *b = c->b;
    int st = tmode == FFC_TANGENT_RANKED
                 ? ffc__bulk_direction_ranked(b, c->nt, c->rho, c->dy, c->dz, c->q, c->gdz, na, c->bad)
                 : ffc__bulk_direction(b, c->nt, c->rho, c->dy, c->dz, c->ap, c->ad, c->q, c->tt, c->ss, na,
                                       c->bad);
    if (st) return st;
    if (*na > c->info->support) c->info->support = *na;
    /* the step of y that the step of z makes: G dz (= dy to the accuracy
     * of the dense solve; the ranked direction made it) */
    if (tmode != FFC_TANGENT_RANKED) st = ffc__bulk_gemv(b, c->m, c->m, 1.0, b->G, b->ld, c->dz, 0.0, c->gdz);
    if (st) return st;
    *g0 = ffc__dotn(c->m, c->rho, c->gdz);
    *whole = 0;
    if (!(*g0 < 0) && tmode == FFC_TANGENT_CONSISTENT) {
        st = ffc__bulk_gemv(b, c->nrb, c->m, 1.0, b->H, c->nrb, c->dz, 0.0, c->hdz);
        if (!st) st = trial(c, 1.0);
        if (st || c->restart) return st;
        *whole = full_step_taken(b, c->m, c->rt, rn, state0);
        if (*whole) return FFC_OK;
        w_at(c, 0.0, c->y);   /* (w back at this iteration's state) */
        st = contact_eval(b, c->fn, c->ctx, c->w, FFC_TANGENT_MATERIAL, &c->nt, &c->fm, c->bad);
        c->info->evals++;
        long nm = 0;
        if (!st) st = ffc__bulk_direction(b, c->nt, c->rho, c->dy, c->dz, c->ap, c->ad, c->q, c->tt, c->ss, &nm,
                                          c->bad);
        if (st) return st;
        if (nm > c->info->support) c->info->support = nm;
        c->info->fallbacks++;
        st = ffc__bulk_gemv(b, c->m, c->m, 1.0, b->G, b->ld, c->dz, 0.0, c->gdz);
        if (st) return st;
        *g0 = ffc__dotn(c->m, c->rho, c->gdz);
    }
    if (!*whole && *g0 < 0) st = ffc__bulk_gemv(b, c->nrb, c->m, 1.0, b->H, c->nrb, c->dz, 0.0, c->hdz);
    return st;
}

/* The step length along dz: the Newton loops' line search (ffc_ls_*),
 * each point a trial; the full step with max_ls = 0 or once taken whole */
static int step_length(cnewton *c, double g0, double rn, const double state0[3], int whole, double *a)
{
    *a = 1.0;
    if (c->o->max_ls <= 0 || whole) return FFC_OK;
    ffc_linesearch ls;
    int st = ffc_ls_start(&ls, c->o->max_ls, c->o->ls_tol, 1.0, g0, rn, 1, 1);
    while (!st && ffc_ls_next(&ls, a) == 1) {
        st = trial(c, *a);
        if (st || c->restart) break;
        const int full = *a == 1.0 && full_step_taken(c->b, c->m, c->rt, rn, state0);
        st = ffc_ls_report(&ls, ffc__dotn(c->m, c->rt, c->gdz), sqrt(ffc__dotn(c->m, c->rt, c->rt)), full);
    }
    return st;
}

/* z += a dz, and y = d0_C + G z, hz = H z by the same steps (G dz and H dz
 * are at hand; recomputed from z every REFRESH iterations); returns the
 * relative size of a full step (1 for a shorter one) */
static double advance(cnewton *c, double a)
{
    const ffc__bulk *b = c->b;
    for (long k = 0; k < c->m; k++) c->z[k] += a * c->dz[k];
    if (c->info->iters % REFRESH == 0) {
        y_of_z(c);
        h_z(c);
    } else {
        for (long k = 0; k < c->m; k++) c->y[k] += a * c->gdz[k];
        for (long k = 0; k < c->nrb; k++) c->hz[k] += a * c->hdz[k];
    }
    for (long k = 0; k < c->nrb; k++) c->hdz[k] = 0.0;
    w_at(c, 0.0, c->y);
    double dn = 0.0, yn = 0.0;
    for (long k = 0; k < c->m; k++) {
        dn += a * a * c->gdz[k] * c->gdz[k];
        yn += c->w[b->dof[k]] * c->w[b->dof[k]];
    }
    return a == 1.0 ? sqrt(dn / fmax(yn, 1e-300)) : 1.0;
}

/* the iteration taken again at the same state (C grew): w as before */
static void again(cnewton *c)
{
    h_z(c);
    w_at(c, 0.0, c->y);
}

/* The iterations: the contact evaluation at z (with the tangent), rho,
 * the convergence test, the direction, the step.  Returns the status (an
 * error) and sets *reason. */
static int iterate(cnewton *c, int *reason)
{
    ffc__bulk *b = c->b;
    const ffc_newton_opts *o = c->o;
    ffc_newton_info *info = c->info;
    int st = FFC_OK, starting = 1, stall = 0, slow = 0, tmode = o->tangent;
    double last = 1.0, rprev = HUGE_VAL;
    long nal = -1, nap = -2;   /* the ranked terms of the last direction and of the one before it (at the state
                                  before; the count stands for the active set) */
    *reason = FFC_NEWTON_MAXIT;
    for (int it = 0; !st; it++) {
        const int tan = it < o->max_iter ? tmode : FFC_TANGENT_NONE;
        st = contact_eval(b, c->fn, c->ctx, c->w, tan, &c->nt, &c->fm, c->bad);
        c->fscale = fmax(c->fscale, c->fm);
        info->evals++;
        if (!st) st = reached(b, tan ? c->nt : 0, tan == FFC_TANGENT_RANKED, &c->nnew, c->bad);
        if (!st && c->nnew && starting) {
            /* the start reaches dofs outside C (at the first call of a load
             * step the rest moves by the whole increment): they join C and
             * are held at u too */
            st = join(c);
            if (!st) st = ffc__bulk_factor_g(b);
            if (st) break;
            start(c);
            it--;
            continue;
        }
        if (!st && c->nnew) st = join(c);
        if (!st) st = force_c(b, c->y, c->Fp, c->bad);
        if (st) break;
        for (long k = 0; k < c->m; k++) c->rho[k] = c->z[k] + c->Fp[k];
        const double rn = sqrt(ffc__dotn(c->m, c->rho, c->rho));
        double state0[3]; /* the contact state at z (the full step's test) */
        memcpy(state0, b->cstate, sizeof state0);
        info->res = rn;
        const double tol = fmax(o->ftol, o->frel * c->fscale);
        /* converged: the force test; or the round-off floor within 1e3 of
         * it: a full step that changed nothing, or two iterations in a row
         * that did not halve the residual (the noise of rho is about
         * eps |Kc G| |z|: with a stiff penalty it lies above a tight tol).
         * An iteration restarted because C grew in its line search is the
         * same state: not counted */
        const int fresh = !c->restart;   /* (a restart repeats the state: its direction replaces the last) */
        if (!c->restart) {
            if (info->nhist < FFC_NEWTON_HIST) info->hist[info->nhist++] = rn;
            stall = rn < 0.5 * rprev ? 0 : stall + 1;
            slow += tmode == FFC_TANGENT_RANKED && rprev < HUGE_VAL && !(rn < 0.1 * rprev) && nal == nap;
            rprev = rn;
        }
        c->restart = 0;
        if ((rn <= tol || ((last <= 1e-14 || stall >= 2) && rn <= 1e3 * tol)) &&
            (info->iters >= o->min_iter || !(rn > 0.0))) { *reason = FFC_NEWTON_CONVERGED; break; }
        if (it == o->max_iter) break;
        if (slow >= RANKED_SLOW) {
            /* ranked directions that RANKED_SLOW times did not gain 10x
             * on an unchanged active set: the geometric terms matter here
             * (a corner, a coarse facet), and the rest of the call takes
             * the consistent tangent (this iteration again, at the same
             * state).  An iteration whose direction had other terms than
             * the one before (the active set moved) is not counted: while
             * the contact zone forms (a load step's first call) the
             * residual rises and falls with the active set whatever the
             * tangent, and a ranked iteration costs a few products of G
             * where a consistent one costs an LU of the tangent's support
             * (Hertz P1 h_c 0.0125, counting them: 53 Newton iterations,
             * 24 of them consistent with supports of up to 1,632 dofs;
             * not: 44, none consistent, the same F to 11 digits) */
            tmode = FFC_TANGENT_CONSISTENT;
            slow = 0;
            info->switched = 1;
            c->restart = 1;
            it--;
            continue;
        }
        long na = 0;
        int whole = 0;
        double g0 = 0.0, a = 1.0;
        starting = 0;
        st = step_direction(c, tmode, rn, state0, &na, &whole, &g0);
        if (fresh) nap = nal;
        nal = na;
        if (st) break;
        if (c->restart) { again(c); it--; continue; }
        if (!whole && !(g0 < 0)) { *reason = FFC_NEWTON_NODESCENT; break; }
        st = step_length(c, g0, rn, state0, whole, &a);
        if (st) break;
        if (c->restart) { again(c); it--; continue; }
        info->iters++;
        last = advance(c, a);
    }
    return st;
}

int ffc__bulk_newton(ffc__bulk *b, long nr, const long rows[], long nc, const long cand[], ffc__contact_fn fn,
                     void *ctx, const double r[], double u[], const ffc_newton_opts *o, ffc_newton_info *info,
                     long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (!b || !fn || !r || !u || !o || !info || (nc > 0 && !cand) || (nr > 0 && !rows)) return FFC_ERR_NULL;
    memset(info, 0, sizeof *info);
    ffc__bulk_clear_error(b);
    b->t_eval = &info->t_eval;
    if (nc < 0 || nr < 0) return FFC_ERR_SIZE;
    if (o->max_iter < 1 || o->max_ls < 0 || !(o->ls_tol > 0 && o->ls_tol < 1) || !(o->ftol > 0) ||
        !isfinite(o->ftol) || !(o->frel >= 0) || !isfinite(o->frel) || o->max_dofs < 0 || o->min_iter < 0 ||
        o->min_iter > 1 ||
        (o->tangent != FFC_TANGENT_CONSISTENT && o->tangent != FFC_TANGENT_MATERIAL && o->tangent != FFC_TANGENT_RANKED))
        return FFC_ERR_VALUE;
    const long n = b->n;
    for (long i = 0; i < n; i++)
        if (!isfinite(r[i]) || !isfinite(u[i])) { *bad = i; return FFC_ERR_NONFINITE; }
    cnewton c = {0};
    c.b = b; c.fn = fn; c.ctx = ctx; c.o = o; c.info = info; c.bad = bad; c.u = u;
    c.w = b->w; c.d0 = b->dx; c.rhs = b->t;
    c.cap = o->max_dofs > 0 && o->max_dofs < b->mmax ? o->max_dofs : b->mmax;
    int reason = FFC_NEWTON_MAXIT;
    int st = setup(&c, nr, rows, nc, cand, r);
    if (!st) st = iterate(&c, &reason);
    info->m = c.m;
    info->reason = reason;
    if (!st && c.buf) {
        /* d = d0 + K^-1 P_C^T z: the state whose residual is rho (d_C = y;
         * not d0 - K^-1 P_C^T F_c, which moves C by G rho and the contact
         * force by about Kc G rho, a hundred times rho at the automatic
         * penalty) */
        double *rhs = c.rhs;
        memset(rhs, 0, (size_t)n * sizeof(double));
        for (long k = 0; k < c.m; k++) rhs[b->dof[k]] = -c.z[k];
        st = ffc__bulk_backsolve(b, rhs, b->r);
        if (!st)
            for (long i = 0; i < n; i++) u[i] += c.d0[i] - b->r[i];
        if (!st) keep_closing(b, rhs, b->r);
    }
    free(c.buf);
    free(c.ibuf);
    if (c.buf) b->info.solves++;
    st = ffc__bulk_note(b, st);
    return st ? st : reason;
}
