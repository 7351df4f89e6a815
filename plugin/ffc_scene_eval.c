/* ffc_scene_eval.c: a scene's search, assembly (links shared over ranks too), augmentation, commit/restore/reset. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ffc.h"
#include "ffc_bulk.h"
#include "ffc_internal.h"
#include "ffc_scene_state.h"

/* (ffc_scene_state.h) */
int ffc__scene_positions(ffc_scene *s, const double u[], long *bad)
{
    for (long i = 0; i < 3 * s->nv; i++) {
        s->x[i] = s->X[i] + u[i];
        if (!isfinite(s->x[i])) { *bad = i / 3; return FFC_ERR_NONFINITE; }
    }
    return FFC_OK;
}

/* The segments of a mortar pair's facet pairs at s->x: its links and
 * moving-edge points (grown as needed; on failure the pair keeps its
 * arrays) and the dual basis of each slave facet from them; returns the
 * link count or an error.  Called at every evaluation: the segments follow
 * the surfaces, and the tangent has their motion (ffc_law.edge; the edge
 * points only when edges != 0: a residual alone does not need them). */
static int mortar_clip(const ffc_scene *s, scene_pair *p, int edges)
{
    long ln = 0, en = 0;
    int st = ffc_mortar_links(s->nper, p->nfs, p->Fs, p->nfm, p->Fm, s->nv, s->x, p->o.qdeg, p->nmp, p->mp, p->lcap, p->links,
                              &ln, edges ? p->ecap : 0, edges ? p->edges : NULL, &en);
    if (st == FFC_ERR_CAPACITY) {
        const long lc = ln > p->lcap ? ln + ln / 4 + 16 : p->lcap, ec = en > p->ecap ? en + en / 4 + 16 : p->ecap;
        ffc_link *l = lc > p->lcap ? malloc(lc * sizeof *l) : NULL;
        ffc_mortar_edge *e = ec > p->ecap ? malloc(ec * sizeof *e) : NULL;
        if ((lc > p->lcap && !l) || (ec > p->ecap && !e)) { free(l); free(e); return FFC_ERR_MEMORY; }
        if (l) { free(p->links); p->links = l; p->lcap = lc; }
        if (e) { free(p->edges); p->edges = e; p->ecap = ec; }
        st = ffc_mortar_links(s->nper, p->nfs, p->Fs, p->nfm, p->Fm, s->nv, s->x, p->o.qdeg, p->nmp, p->mp, p->lcap, p->links,
                              &ln, edges ? p->ecap : 0, edges ? p->edges : NULL, &en);
    }
    if (st < 0) return st;
    p->nl = ln;
    p->ne = en;
    /* the dual basis of each facet from its consecutive links */
    for (long f = 0; f < p->nfs; f++)
        for (int i = 0; i < 9; i++) p->dual[9 * f + i] = i % 4 == 0;
    for (long a = 0; a < p->nl;) {
        const long f = p->links[a].sf;
        ffc__dual_moments m;
        memset(&m, 0, sizeof m);
        for (; a < p->nl && p->links[a].sf == f; a++) ffc__dual_add(&m, p->links[a].xs, p->links[a].w);
        ffc__dual_matrix(&m, (double(*)[3])(p->dual + 9 * f));
    }
    return st;
}

/* A mortar pair's search at s->x: the facet pairs (ffc_mortar_pairs),
 * then their segments; returns the link count or an error. */
static int mortar_search(const ffc_scene *s, scene_pair *p)
{
    long need = 0;
    int st = ffc_mortar_pairs(p->tree, p->nfs, p->Fs, s->nv, s->x, &p->o.search, p->mpcap, p->mp, &need);
    if (st == FFC_ERR_CAPACITY) {
        const long cap = need + need / 4 + 16;
        long *m = malloc(2 * cap * sizeof *m);
        if (!m) return FFC_ERR_MEMORY;
        st = ffc_mortar_pairs(p->tree, p->nfs, p->Fs, s->nv, s->x, &p->o.search, cap, m, &need);
        if (st < 0) { free(m); return st; }
        free(p->mp);
        p->mp = m;
        p->mpcap = cap;
    }
    if (st < 0) return st;
    p->nmp = st;
    return mortar_clip(s, p, 0);
}

/* Every mortar pair's segments at u (positions into s->x); edges: with
 * their moving-edge points (for a consistent tangent) */
static int mortar_follow(ffc_scene *s, const double u[], int edges, long *bad)
{
    int any = 0;
    for (int k = 0; k < s->np; k++) any |= s->p[k].o.method == FFC_METHOD_MORTAR;
    if (!any) return FFC_OK;
    int st = ffc__scene_positions(s, u, bad);
    if (st) return st;
    for (int k = 0; k < s->np; k++) {
        if (s->p[k].o.method != FFC_METHOD_MORTAR) continue;
        st = mortar_clip(s, &s->p[k], edges);
        if (st < 0) { *bad = k; return st; }
    }
    return FFC_OK;
}

int ffc_scene_search(ffc_scene *s, const double u[], long *linked, long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (!s || !u) return FFC_ERR_NULL;
    int st = ffc__scene_positions(s, u, bad);
    if (st) return st;
    long total = 0;
    for (int k = 0; k < s->np; k++) {
        scene_pair *p = &s->p[k];
        if (p->o.method == FFC_METHOD_NTS) continue; /* its nodes are located by ffc_scene_nts_rows */
        if (p->obst) {
            st = ffc_obstacle_search(&p->ob, s->nper, p->nfs, p->Fs, s->nv, s->x, p->o.qdeg, &p->o.search, p->nl,
                                     p->links);
            if (st < 0) { *bad = k; return st; }
            total += st;
            continue;
        }
        /* the tree keeps its order and refits its boxes as the surfaces move */
        st = p->tree ? ffc_tree_refit(p->tree, s->x) : ffc_tree_build(s->nper, p->nfm, p->Fm, s->nv, s->x, &p->tree);
        if (st) { *bad = k; return st; }
        st = p->o.method == FFC_METHOD_MORTAR
                 ? mortar_search(s, p)
                 : ffc_search(p->tree, s->nper, p->nfs, p->Fs, s->nv, s->x, p->o.qdeg, &p->o.search, p->nl, p->links);
        if (st < 0) { *bad = k; return st; }
        total += st;
    }
    if (linked) *linked = total;
    return FFC_OK;
}

/* (ffc_scene_state.h) */
pair_call ffc__pair_view(const ffc_scene *s, const scene_pair *p, const double u[], int tangent)
{
    pair_call c;
    ffc_pair *v = &c.v;
    ffc_law *law = &c.law;
    ffc_effects *fx = &c.fx;
    v->ns = v->nm = s->nper;
    v->nfs = p->nfs;
    v->Fs = p->Fs;
    v->nfm = p->nfm;
    v->Fm = p->Fm;
    v->nv = s->nv;
    v->X = s->X;
    v->u = u;
    v->u_prev = s->u_prev;
    v->v = s->v;
    v->obst = p->obst ? &p->ob : NULL;
    if (p->obst) v->nm = 0;
    memset(law, 0, sizeof *law);
    law->eps_n = p->o.eps_n;
    law->nodal = p->o.nodal;
    law->tangent = tangent == FFC_TANGENT_NONE ? FFC_TANGENT_CONSISTENT : tangent;
    law->mu = p->o.mu;
    /* the default tangential penalty: eps_N per unit slip; in the velocity
     * form eps_N / (dv/du), the same stiffness against the step's slip */
    law->eps_t = p->o.eps_t > 0 ? p->o.eps_t
                                : (s->fx.dynamic ? (s->dvdu > 0 ? p->o.eps_n / s->dvdu : p->o.eps_n * s->dt) : p->o.eps_n);
    law->dt = s->dt;
    law->dvdu = s->dvdu;
    law->fixed = s->fixed;
    law->dual = p->o.method == FFC_METHOD_MORTAR && p->o.dual ? p->dual : NULL;
    law->tdual = p->o.dual_t; /* (augmented Lagrangian only: ffc_pair_opts_check) */
    law->nedge = p->o.method == FFC_METHOD_MORTAR ? p->ne : 0;
    law->edge = p->edges;
    *fx = s->fx;
    fx->friction = p->o.mu > 0; /* a frictionless pair computes no friction term */
    return c;
}

/* (ffc_scene_state.h) */
int ffc__penalties_set(const ffc_scene *s, long *bad)
{
    for (int k = 0; k < s->np; k++)
        if (s->p[k].o.method == FFC_METHOD_AL && !(s->p[k].o.eps_n > 0)) { *bad = k; return 0; }
    return 1;
}

/* Keep the augmentation's own statistics across an assembly. */
static void keep_augment_stats(ffc_stats *dst, const ffc_stats *old)
{
    dst->max_dlam = old->max_dlam;
    dst->max_dlam_t = old->max_dlam_t;
    dst->max_pen_node = old->max_pen_node;
}


/* rank r's n values at buf + r n of all (each rank's own filled), gathered;
 * every rank's status st first: the first nonzero one in rank order, or
 * FFC_ERR_SIZE when the counts differ */
static int share_gather(const share_ctx *c, int st, long n, double all[])
{
    double *hd = malloc(2 * (size_t)c->size * sizeof *hd);
    long *cnt = malloc((size_t)c->size * sizeof *cnt);
    if (!hd || !cnt) { free(hd); free(cnt); return FFC_ERR_MEMORY; }   /* (MPI aborts the run before malloc fails here) */
    for (int r = 0; r < c->size; r++) { cnt[r] = 2; hd[2 * r] = hd[2 * r + 1] = 0.0; }
    hd[2 * c->rank] = st;
    hd[2 * c->rank + 1] = (double)n;
    int g = ffc__mpi_allgather(c->comm, hd, cnt);
    for (int r = 0; r < c->size && !g; r++)
        if (hd[2 * r] != 0.0) g = (int)hd[2 * r];
    for (int r = 0; r < c->size && !g; r++)
        if (hd[2 * r + 1] != (double)n) g = FFC_ERR_SIZE;
    for (int r = 0; r < c->size; r++) cnt[r] = n;
    if (!g) g = ffc__mpi_allgather(c->comm, all, cnt);
    free(hd);
    free(cnt);
    return g;
}

/* ffc_law.nsum: the shares' node sums, added in rank order */
static int share_nsum(void *ctx, int st, long n, double buf[])
{
    const share_ctx *c = ctx;
    double *all = st ? NULL : malloc((size_t)(c->size * n > 0 ? c->size * n : 1) * sizeof *all);
    if (!st && !all) st = FFC_ERR_MEMORY;
    if (all) memcpy(all + c->rank * n, buf, (size_t)n * sizeof *all);
    st = share_gather(c, st, st ? 0 : n, all);
    for (long i = 0; i < n && !st; i++) {
        double t = 0.0;
        for (int r = 0; r < c->size; r++) t += all[r * n + i];
        buf[i] = t;
    }
    free(all);
    return st;
}

/* the distinct nodes of the slave and master facets of a pair's linked
 * links (where its residual may be nonzero), ascending, into v (room: nv;
 * mark: nv zeros, left zero); their count */
static long pair_nodes(const ffc_scene *s, const scene_pair *p, unsigned char mark[], long v[])
{
    long lo = s->nv, hi = -1;
    for (long k = 0; k < p->nl; k++) {
        const ffc_link *L = &p->links[k];
        if (L->mf < 0) continue;
        for (int a = 0; a < (p->obst ? 1 : 2) * s->nper; a++) {
            const long x = a < s->nper ? p->Fs[L->sf * s->nper + a] : p->Fm[L->mf * s->nper + a - s->nper];
            mark[x] = 1;
            if (x < lo) lo = x;
            if (x > hi) hi = x;
        }
    }
    long m = 0;
    for (long i = lo; i <= hi; i++)
        if (mark[i]) { v[m++] = i; mark[i] = 0; }
    return m;
}

/* pair_shared's link statistics *st over the ranks of c: counts and forces
 * summed, maxima (cnt[c->size]: work); the gathers' status */
static int share_stats(const share_ctx *c, ffc_stats *st, long cnt[])
{
    int gs = FFC_OK;
    double *sb = malloc(10 * (size_t)c->size * sizeof *sb);
    if (!ffc__mpi_min(c->comm, sb != NULL)) gs = FFC_ERR_MEMORY;
    else {
        double *q = sb + 10 * c->rank;
        q[0] = (double)st->linked; q[1] = (double)st->active;
        for (int i = 0; i < 3; i++) { q[2 + i] = st->force[i]; q[5 + i] = st->force_t[i]; }
        q[8] = st->max_pen; q[9] = st->max_tn;
        for (int r = 0; r < c->size; r++) cnt[r] = 10;
        gs = ffc__mpi_allgather(c->comm, sb, cnt);
        if (!gs) {
            ffc_stats *t = st;
            t->linked = t->active = 0;
            t->max_pen = t->max_tn = 0.0;
            for (int i = 0; i < 3; i++) t->force[i] = t->force_t[i] = 0.0;
            for (int r = 0; r < c->size; r++) {
                const double *a = sb + 10 * r;
                t->linked += (long)a[0];
                t->active += (long)a[1];
                for (int i = 0; i < 3; i++) { t->force[i] += a[2 + i]; t->force_t[i] += a[5 + i]; }
                t->max_pen = fmax(t->max_pen, a[8]);
                t->max_tn = fmax(t->max_tn, a[9]);
            }
        }
    }
    free(sb);
    return gs;
}

/* Pair p's contact on the ranks of c, each its share of the links (law: the
 * pair's, shared out here): the residual added into R, the triplets into
 * Ti.. (room: their capacity; *n the count, every rank's), p->st the
 * statistics; the status is every rank's. */
static int pair_shared(const ffc_scene *s, scene_pair *p, const share_ctx *c, ffc_law law, const ffc_effects *fx,
                       const ffc_pair *v, double R[], long room, long Ti[], long Tj[], double Tv[], long *n, long *bad)
{
    unsigned char *sel = malloc((size_t)(p->nl > 0 ? p->nl : 1) + (size_t)s->nv);   /* (and the nodes' marks) */
    long *nodes = malloc((size_t)(s->nv > 0 ? s->nv : 1) * sizeof *nodes);
    if (sel) memset(sel + (p->nl > 0 ? p->nl : 1), 0, (size_t)s->nv);
    double *Rp = calloc((size_t)(3 * s->nv), sizeof *Rp);
    int st = sel && nodes && Rp ? FFC_OK : FFC_ERR_MEMORY;
    long nloc = 0;
    if (!st) {
        /* the linked links (those with a master facet: the others cost
         * nothing) in equal contiguous shares, in the links' order (by
         * slave facet) */
        long nlinked = 0;
        for (long k = 0; k < p->nl; k++) nlinked += p->links[k].mf >= 0;
        const long lo = nlinked * c->rank / c->size, hi = nlinked * (c->rank + 1) / c->size;
        for (long k = 0, j = 0; k < p->nl; k++) {
            sel[k] = p->links[k].mf >= 0 && j >= lo && j < hi;
            j += p->links[k].mf >= 0;
        }
        law.lsel = sel;
        law.nsum = share_nsum;
        law.nsum_ctx = (void *)c;
        st = ffc_assemble(fx, v, ffc__pair_qdeg(p), p->nl, p->links, p->lam, p->lam_t, &law, Rp, room, Ti, Tj, Tv,
                          &nloc, &p->st, bad);
    } else {   /* (the node sums' exchange, as the kernel would have made it) */
        double none = 0.0;
        share_nsum((void *)c, st, 0, &none);
    }
    /* every rank's status and triplet count */
    const int over = st == FFC_ERR_CAPACITY;
    long *cnt = malloc((size_t)c->size * sizeof *cnt);
    double *hd = malloc(3 * (size_t)c->size * sizeof *hd);
    if (!cnt || !hd) { free(cnt); free(hd); free(sel); free(nodes); free(Rp); return FFC_ERR_MEMORY; }
    for (int r = 0; r < c->size; r++) { cnt[r] = 3; hd[3 * r] = hd[3 * r + 1] = hd[3 * r + 2] = 0.0; }
    hd[3 * c->rank] = over ? FFC_OK : st;
    hd[3 * c->rank + 1] = (double)nloc;
    hd[3 * c->rank + 2] = over;
    int g = ffc__mpi_allgather(c->comm, hd, cnt);
    long total = 0;
    int anyover = 0;
    for (int r = 0; r < c->size && !g; r++) {
        if (hd[3 * r] != 0.0) g = (int)hd[3 * r];
        total += (long)hd[3 * r + 1];
        anyover |= hd[3 * r + 2] != 0.0;
    }
    *n = total;
    if (!g && (anyover || total > room)) g = FFC_ERR_CAPACITY;
    /* the residual at the pair's dofs */
    const long nn = g ? 0 : pair_nodes(s, p, sel + (p->nl > 0 ? p->nl : 1), nodes), m = 3 * nn;
    double *all = g ? NULL : malloc((size_t)(c->size * m > 0 ? c->size * m : 1) * sizeof *all);
    int gs = FFC_OK;   /* (the gathers' status; with capacity short, the statistics are still gathered) */
    if (!g) {
        if (!all) gs = FFC_ERR_MEMORY;
        for (long i = 0; i < nn && all; i++)
            for (int k = 0; k < 3; k++) all[c->rank * m + 3 * i + k] = Rp[3 * nodes[i] + k];
        gs = share_gather(c, gs, gs ? 0 : m, all);
        for (long i = 0; i < nn && !gs; i++)
            for (int k = 0; k < 3; k++) {
                double t = 0.0;
                for (int r = 0; r < c->size; r++) t += all[r * m + 3 * i + k];
                R[3 * nodes[i] + k] += t;
            }
        /* the triplets, in rank order */
        double *tr = gs ? NULL : malloc((size_t)(3 * total > 0 ? 3 * total : 1) * sizeof *tr);
        if (!gs && !ffc__mpi_min(c->comm, tr != NULL)) gs = FFC_ERR_MEMORY;   /* (alike on every rank) */
        if (!gs) {
            long off = 0;
            for (int r = 0; r < c->rank; r++) off += (long)hd[3 * r + 1];
            for (long e = 0; e < nloc; e++) {
                tr[3 * (off + e)] = (double)Ti[e];
                tr[3 * (off + e) + 1] = (double)Tj[e];
                tr[3 * (off + e) + 2] = Tv[e];
            }
            for (int r = 0; r < c->size; r++) cnt[r] = 3 * (long)hd[3 * r + 1];
            gs = ffc__mpi_allgather(c->comm, tr, cnt);
            for (long e = 0; e < total && !gs; e++) {
                Ti[e] = (long)tr[3 * e];
                Tj[e] = (long)tr[3 * e + 1];
                Tv[e] = tr[3 * e + 2];
            }
        }
        free(tr);
    }
    /* the link statistics: counts and forces summed, maxima (the node
     * statistics are every rank's alike) */
    if (!gs && (!g || g == FFC_ERR_CAPACITY)) gs = share_stats(c, &p->st, cnt);
    free(all);
    free(cnt);
    free(hd);
    free(sel);
    free(nodes);
    free(Rp);
    return g ? g : gs;
}

int ffc_scene_assemble(ffc_scene *s, const double u[], int tangent, double R[], long cap, long Ti[], long Tj[],
                       double Tv[], long *ntrip, long *bad)
{
    return ffc__scene_assemble(s, u, tangent, R, cap, Ti, Tj, Tv, ntrip, bad, NULL, NULL);
}

/* (ffc_scene_state.h) */
int ffc__scene_assemble(ffc_scene *s, const double u[], int tangent, double R[], long cap, long Ti[], long Tj[],
                        double Tv[], long *ntrip, long *bad, const share_ctx *share, int *shared)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (!s || !u || !R || !ntrip) return FFC_ERR_NULL;
    if (tangent != FFC_TANGENT_NONE && tangent != FFC_TANGENT_CONSISTENT && tangent != FFC_TANGENT_MATERIAL &&
        tangent != FFC_TANGENT_RANKED)
        return FFC_ERR_VALUE;
    for (int k = 0; k < s->np && tangent == FFC_TANGENT_RANKED; k++)
        if (s->p[k].o.method != FFC_METHOD_NTS && !s->p[k].o.nodal) { *bad = k; return FFC_ERR_VALUE; }
    if (tangent != FFC_TANGENT_NONE && (!Ti || !Tj || !Tv)) return FFC_ERR_NULL;
    if (cap < 0) return FFC_ERR_SIZE;
    if (!ffc__penalties_set(s, bad)) return FFC_ERR_VALUE;
    int fs = mortar_follow(s, u, tangent == FFC_TANGENT_CONSISTENT, bad); /* the mortar segments at u */
    if (fs) return fs;
    long nt = 0, nterm = 0; /* (ranked: the terms of the pairs before) */
    int over = 0;
    for (int k = 0; k < s->np; k++) {
        scene_pair *p = &s->p[k];
        if (p->o.method == FFC_METHOD_NTS) continue; /* constraint rows instead: ffc_scene_nts_rows */
        const pair_call c = ffc__pair_view(s, p, u, tangent);
        const long room = over ? 0 : cap - nt;
        long n = 0;
        ffc_stats old = p->st;
        const int pair_is_shared = share && p->o.method == FFC_METHOD_AL && p->o.nodal && !c.law.dual && c.law.nedge == 0 &&
                           (tangent == FFC_TANGENT_NONE || tangent == FFC_TANGENT_RANKED);
        if (shared && pair_is_shared) *shared = 1;
        int st = pair_is_shared ? pair_shared(s, p, share, c.law, &c.fx, &c.v, R, tangent == FFC_TANGENT_NONE ? 0 : room,
                                      tangent == FFC_TANGENT_NONE ? NULL : Ti + (over ? 0 : nt),
                                      tangent == FFC_TANGENT_NONE ? NULL : Tj + (over ? 0 : nt),
                                      tangent == FFC_TANGENT_NONE ? NULL : Tv + (over ? 0 : nt), &n, bad)
                        : ffc_assemble(&c.fx, &c.v, ffc__pair_qdeg(p), p->nl, p->links, p->lam, p->lam_t, &c.law,
                              R, room,
                              tangent == FFC_TANGENT_NONE ? NULL : Ti + (over ? 0 : nt),
                              tangent == FFC_TANGENT_NONE ? NULL : Tj + (over ? 0 : nt),
                              tangent == FFC_TANGENT_NONE ? NULL : Tv + (over ? 0 : nt), &n, &p->st, bad);
        if (st == FFC_ERR_CAPACITY) over = 1;
        else if (st) return st;
        keep_augment_stats(&p->st, &old);
        if (tangent == FFC_TANGENT_RANKED && !over) { /* this pair's terms after the others' */
            long top = 0;
            for (long e = nt; e < nt + n; e++) {
                if (Tj[e] / 2 + 1 > top) top = Tj[e] / 2 + 1;
                Tj[e] += 2 * nterm;
            }
            nterm += top;
        }
        nt += n;
    }
    *ntrip = nt;
    return over ? FFC_ERR_CAPACITY : FFC_OK;
}

int ffc_scene_augment(ffc_scene *s, const double u[], long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (!s || !u) return FFC_ERR_NULL;
    if (!ffc__penalties_set(s, bad)) return FFC_ERR_VALUE;
    int fs = mortar_follow(s, u, 0, bad); /* the mortar segments at u */
    if (fs) return fs;
    for (int k = 0; k < s->np; k++) {
        scene_pair *p = &s->p[k];
        if (p->o.method == FFC_METHOD_NTS) continue;
        const pair_call c = ffc__pair_view(s, p, u, FFC_TANGENT_NONE);
        int st = ffc__augment(&c.fx, &c.v, ffc__pair_qdeg(p), p->nl, p->links, p->lam, p->lam_t, &c.law, &p->st,
                              p->fst, bad);
        if (st) return st;
    }
    return FFC_OK;
}

int ffc_scene_commit(ffc_scene *s, const double u[])
{
    if (!s || !u) return FFC_ERR_NULL;
    for (long i = 0; i < 3 * s->nv; i++)
        if (!isfinite(u[i])) return FFC_ERR_NONFINITE;
    memcpy(s->u_prev, u, 3 * s->nv * sizeof *u);
    for (int k = 0; k < s->np; k++) {
        scene_pair *p = &s->p[k];
        memcpy(p->lam0, p->lam, p->nlam * sizeof *p->lam);
        memcpy(p->lam_t0, p->lam_t, 3 * p->nlam * sizeof *p->lam_t);
        memcpy(p->fst0, p->fst, (size_t)p->nlam);
        p->st_step = p->st;
        if (p->obst) { p->ob0 = p->ob; ffc__obstacle_motion(s, p); }
        if (p->nodes) {
            memcpy(p->nodes0, p->nodes, p->nn * sizeof *p->nodes);
            p->nst_step = p->nst;
        }
    }
    return FFC_OK;
}

int ffc_scene_restore(ffc_scene *s)
{
    if (!s) return FFC_ERR_NULL;
    for (int k = 0; k < s->np; k++) {
        scene_pair *p = &s->p[k];
        memcpy(p->lam, p->lam0, p->nlam * sizeof *p->lam);
        memcpy(p->lam_t, p->lam_t0, 3 * p->nlam * sizeof *p->lam_t);
        memcpy(p->fst, p->fst0, (size_t)p->nlam);
        if (p->nodes) memcpy(p->nodes, p->nodes0, p->nn * sizeof *p->nodes);
    }
    return FFC_OK;
}

int ffc_scene_reset(ffc_scene *s)
{
    if (!s) return FFC_ERR_NULL;
    memset(s->u_prev, 0, 3 * s->nv * sizeof *s->u_prev);
    memset(s->v, 0, 3 * s->nv * sizeof *s->v);
    for (int k = 0; k < s->np; k++) {
        scene_pair *p = &s->p[k];
        memset(p->lam, 0, p->nlam * sizeof *p->lam);
        memset(p->lam0, 0, p->nlam * sizeof *p->lam0);
        memset(p->lam_t, 0, 3 * p->nlam * sizeof *p->lam_t);
        memset(p->lam_t0, 0, 3 * p->nlam * sizeof *p->lam_t0);
        memset(p->fst, 0, (size_t)p->nlam);
        memset(p->fst0, 0, (size_t)p->nlam);
        memset(&p->st, 0, sizeof p->st);
        memset(&p->st_step, 0, sizeof p->st_step);
        if (p->obst) { p->ob0 = p->ob; ffc__obstacle_motion(s, p); }
        for (long l = 0; l < p->nl; l++) p->links[l].mf = -1;
        if (p->o.method == FFC_METHOD_MORTAR) p->nl = p->ne = p->nmp = 0;
        if (p->nodes) {
            int st = ffc__nts_alloc(s, p);
            if (st) return st;
        }
    }
    return FFC_OK;
}
