/* ffc_scene.c: a scene's creation, effects, settings, bulk law, line search; its pairs, fixed dofs, motion. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ffc.h"
#include "ffc_bulk.h"
#include "ffc_internal.h"
#include "ffc_scene_state.h"

ffc_pair_opts ffc_pair_defaults(void)
{
    ffc_pair_opts o;
    memset(&o, 0, sizeof o);
    o.method = FFC_METHOD_AL;
    o.qdeg = 4;
    o.nodal = 1;
    o.mu = 0.0;
    o.eps_n = 0.0;
    o.eps_t = 0.0;
    o.search = ffc_search_defaults();
    o.mu_d = -1.0;
    o.gtol = 0.0;
    o.ftol = 1e-9;
    o.max_flips = 4;
    o.scale = 0.0;
    o.dual = 1;
    o.dual_t = 0;
    return o;
}

static int finite_nonneg(double a) { return a >= 0 && isfinite(a); }

int ffc_pair_opts_check(const ffc_pair_opts *o)
{
    if (!o) return FFC_ERR_NULL;
    if (o->method != FFC_METHOD_AL && o->method != FFC_METHOD_NTS && o->method != FFC_METHOD_MORTAR)
        return FFC_ERR_VALUE;
    if ((o->dual != 0 && o->dual != 1) || (o->dual_t != 0 && o->dual_t != 1) || (o->method == FFC_METHOD_MORTAR && o->nodal != 1))
        return FFC_ERR_VALUE;
    if (o->dual_t && (o->method != FFC_METHOD_AL || o->nodal != 1)) return FFC_ERR_VALUE; /* (where it acts) */
    if (!isfinite(o->mu_d) || o->mu_d > o->mu || !finite_nonneg(o->gtol) || !finite_nonneg(o->ftol) ||
        o->max_flips < 1 || !finite_nonneg(o->scale))
        return FFC_ERR_VALUE;
    if (ffc_quad_size(o->qdeg) < 0) return FFC_ERR_QUAD;
    if (o->nodal != 0 && o->nodal != 1) return FFC_ERR_VALUE;
    if (!finite_nonneg(o->mu) || !finite_nonneg(o->eps_t)) return FFC_ERR_VALUE;
    if (!finite_nonneg(o->eps_n)) return FFC_ERR_VALUE; /* 0: not set yet */
    if (!finite_nonneg(o->search.capture_rel) || !finite_nonneg(o->search.capture_abs) ||
        !finite_nonneg(o->search.edge_tol) || (o->search.self != 0 && o->search.self != 1))
        return FFC_ERR_VALUE;
    if (o->search.self && o->method == FFC_METHOD_NTS) return FFC_ERR_VALUE; /* (the searches' exclusions: ffc_search, ffc_mortar_pairs) */
    return FFC_OK;
}

static void pair_free(scene_pair *p)
{
    free(p->Fs);
    free(p->Fm);
    ffc_tree_free(p->tree);
    free(p->links);
    free(p->dual);
    free(p->mp);
    free(p->edges);
    free(p->lam);
    free(p->lam_t);
    free(p->lam0);
    free(p->lam_t0);
    free(p->fst);
    free(p->fst0);
    free(p->nodes);
    free(p->nodes0);
    memset(p, 0, sizeof *p);
}

void ffc_scene_free(ffc_scene *s)
{
    if (!s) return;
    for (int k = 0; k < s->np; k++) pair_free(&s->p[k]);
    free(s->p);
    free(s->X);
    free(s->T);
    free(s->v0);
    free(s->u_prev);
    free(s->v);
    free(s->x);
    ffc__bulk_free(s->bulk);
    free(s->fixed);
    free(s);
}

int ffc_scene_create(int nper, long nv, const double X[], long nt, const long T[],
                     const ffc_effects *effects, ffc_scene **out)
{
    if (!out) return FFC_ERR_NULL;
    *out = NULL;
    if (!X || !effects || (nt > 0 && !T)) return FFC_ERR_NULL;
    if (nper != 3 && nper != 6) return FFC_ERR_NODES;
    if (nv <= 0 || nt < 0) return FFC_ERR_SIZE;
    if ((effects->friction != 0 && effects->friction != 1) || (effects->dynamic != 0 && effects->dynamic != 1) ||
        (effects->finite_def != 0 && effects->finite_def != 1))
        return FFC_ERR_VALUE;
    for (long i = 0; i < 3 * nv; i++)
        if (!isfinite(X[i])) return FFC_ERR_NONFINITE;
    for (long i = 0; i < 4 * nt; i++)
        if (T[i] < 0 || T[i] >= nv) return FFC_ERR_INDEX;
    ffc_scene *s = calloc(1, sizeof *s);
    if (!s) return FFC_ERR_MEMORY;
    s->nper = nper;
    s->nv = nv;
    s->nt = nt;
    s->fx = *effects;
    s->X = malloc(3 * nv * sizeof *s->X);
    s->u_prev = calloc(3 * nv, sizeof *s->u_prev);
    s->v = calloc(3 * nv, sizeof *s->v);
    s->x = malloc(3 * nv * sizeof *s->x);
    s->T = nt ? malloc(4 * nt * sizeof *s->T) : NULL;
    s->v0 = nt ? malloc(nt * sizeof *s->v0) : NULL;
    if (!s->X || !s->u_prev || !s->v || !s->x || (nt && (!s->T || !s->v0))) {
        ffc_scene_free(s);
        return FFC_ERR_MEMORY;
    }
    memcpy(s->X, X, 3 * nv * sizeof *X);
    if (nt) memcpy(s->T, T, 4 * nt * sizeof *T);
    ffc__tet_volumes(nt, s->T, s->X, s->v0);
    ffc_settings_defaults(&s->set);
    s->law = ffc_bulk_law_of(effects->finite_def ? FFC_BULK_NEOHOOKEAN : FFC_BULK_LINEAR);
    *out = s;
    return FFC_OK;
}

int ffc_scene_npairs(const ffc_scene *s) { return s ? s->np : FFC_ERR_NULL; }

int ffc_scene_effects(const ffc_scene *s, ffc_effects *fx)
{
    if (!s || !fx) return FFC_ERR_NULL;
    *fx = s->fx;
    return FFC_OK;
}

ffc_settings *ffc_scene_settings(ffc_scene *s) { return s ? &s->set : NULL; }

ffc_linesearch *ffc_scene_line_search(ffc_scene *s) { return s ? &s->ls : NULL; }

ffc_bulk_law ffc_bulk_law_of(ffc_bulk_kind kind)
{
    switch (kind) {
    case FFC_BULK_NEOHOOKEAN: return (ffc_bulk_law){FFC_BULK_NEOHOOKEAN, 0, 1, 1};
    case FFC_BULK_SVK: return (ffc_bulk_law){FFC_BULK_SVK, 0, 1, 1};
    case FFC_BULK_MOONEYRIVLIN: return (ffc_bulk_law){FFC_BULK_MOONEYRIVLIN, 0, 1, 1};
    case FFC_BULK_USER: return (ffc_bulk_law){FFC_BULK_USER, 0, 1, 0};
    default: return (ffc_bulk_law){FFC_BULK_LINEAR, 1, 1, 0};
    }
}

int ffc_scene_set_law(ffc_scene *s, const ffc_bulk_law *law)
{
    if (!s || !law) return FFC_ERR_NULL;
    if ((law->kind != FFC_BULK_LINEAR && law->kind != FFC_BULK_NEOHOOKEAN && law->kind != FFC_BULK_USER &&
         law->kind != FFC_BULK_SVK && law->kind != FFC_BULK_MOONEYRIVLIN) ||
        (law->linear != 0 && law->linear != 1) || (law->symmetric != 0 && law->symmetric != 1) ||
        (law->finite != 0 && law->finite != 1) || (law->linear && law->finite))
        return FFC_ERR_VALUE;
    if (law->kind != FFC_BULK_USER) {   /* a built-in law is what it declares */
        const ffc_bulk_law b = ffc_bulk_law_of(law->kind);
        if (law->linear != b.linear || law->symmetric != b.symmetric || law->finite != b.finite) return FFC_ERR_VALUE;
    }
    s->law = *law;
    s->fx.finite_def = law->finite;
    return FFC_OK;
}

int ffc_scene_law(const ffc_scene *s, ffc_bulk_law *law)
{
    if (!s || !law) return FFC_ERR_NULL;
    *law = s->law;
    return FFC_OK;
}

/* The pair's facet nodes in range; *bad = the facet entry at fault. */
static int check_nodes(long n, const long F[], long nv, long *bad)
{
    for (long i = 0; i < n; i++)
        if (F[i] < 0 || F[i] >= nv) { *bad = i; return FFC_ERR_INDEX; }
    return FFC_OK;
}

/* FFC_ERR_FUSED (*bad = the slave facet) when a slave facet's vertices are
 * all master nodes: the two surfaces share their nodes (bodies meshed as
 * one), and there is no contact to compute.  Facets that only share an
 * edge or a vertex (faces of one body meeting at a corner) pass. */
static int check_fused(int nper, long nfs, const long Fs[], long nfm, const long Fm[], long nv, long *bad)
{
    unsigned char *m = calloc(nv, 1);
    if (!m) return FFC_ERR_MEMORY;
    for (long i = 0; i < nfm * nper; i++) m[Fm[i]] = 1;
    int st = FFC_OK;
    for (long f = 0; f < nfs && !st; f++)
        if (m[Fs[nper * f]] && m[Fs[nper * f + 1]] && m[Fs[nper * f + 2]]) { *bad = f; st = FFC_ERR_FUSED; }
    free(m);
    return st;
}

/* FFC_ERR_INTERIOR (*bad = f for slave facet f, nfs + f for master facet
 * f) when a facet's three corners belong to two of the scene's
 * tetrahedra: the facet lies inside the volume mesh (a labelled surface
 * between two regions meshed as one, gmsh's BooleanFragments), its two
 * sides share their nodes and can neither separate nor press on each
 * other. A face on the boundary has one tetrahedron. Nothing to check
 * without tetrahedra (nt = 0). */
static int check_interior(const ffc_scene *s, long nfs, const long Fs[], long nfm, const long Fm[], long *bad)
{
    if (s->nt <= 0) return FFC_OK;
    const long nv = s->nv, nt = s->nt;
    long *start = calloc(nv + 1, sizeof *start), *tets = malloc(4 * nt * sizeof *tets);
    if (!start || !tets) { free(start); free(tets); return FFC_ERR_MEMORY; }
    /* the tetrahedra at each node (CSR: start[v] .. start[v + 1]) */
    for (long i = 0; i < 4 * nt; i++) start[s->T[i] + 1]++;
    for (long v = 0; v < nv; v++) start[v + 1] += start[v];
    for (long i = 0; i < 4 * nt; i++) tets[start[s->T[i]]++] = i / 4;
    for (long v = nv; v > 0; v--) start[v] = start[v - 1];
    start[0] = 0;
    int st = FFC_OK;
    for (long f = 0; f < nfs + nfm && !st; f++) {
        const long *c = f < nfs ? Fs + s->nper * f : Fm + s->nper * (f - nfs);
        int shared = 0;
        for (long k = start[c[0]]; k < start[c[0] + 1]; k++) {
            const long *t = s->T + 4 * tets[k];
            int has1 = 0, has2 = 0;
            for (int j = 0; j < 4; j++) { has1 |= t[j] == c[1]; has2 |= t[j] == c[2]; }
            shared += has1 && has2;
        }
        if (shared > 1) { *bad = f; st = FFC_ERR_INTERIOR; }
    }
    free(start); free(tets);
    return st;
}

/* Multiplier arrays of the pair for its law (sizes nv or nl), zeroed; on
 * failure the pair keeps the arrays it had. */
static int pair_alloc_lambda(scene_pair *p, long nv)
{
    const long n = p->o.nodal ? nv : p->nl;
    double *l = calloc(n, sizeof *l), *l0 = calloc(n, sizeof *l0), *lt = calloc(3 * n, sizeof *lt),
           *lt0 = calloc(3 * n, sizeof *lt0);
    signed char *f = calloc(n > 0 ? n : 1, 1), *f0 = calloc(n > 0 ? n : 1, 1);
    if (!l || !l0 || !lt || !lt0 || !f || !f0) {
        free(l); free(l0); free(lt); free(lt0); free(f); free(f0);
        return FFC_ERR_MEMORY;
    }
    free(p->lam); free(p->lam_t); free(p->lam0); free(p->lam_t0); free(p->fst); free(p->fst0);
    p->fst = f;
    p->fst0 = f0;
    p->nlam = n;
    p->lam = l;
    p->lam0 = l0;
    p->lam_t = lt;
    p->lam_t0 = lt0;
    return FFC_OK;
}

/* Links without a partner, at the pair's quadrature points; on failure
 * the pair keeps the links it had. */
static int pair_alloc_links(scene_pair *p)
{
    if (p->o.method == FFC_METHOD_MORTAR) { /* links come from each search (none before the first: an
                                                 assembly then adds nothing); the dual basis starts standard */
        double *d = p->dual ? p->dual : malloc(9 * p->nfs * sizeof *d);
        if (!d) return FFC_ERR_MEMORY;
        if (!p->links) {
            p->links = malloc(16 * sizeof *p->links);
            if (!p->links) { if (d != p->dual) free(d); return FFC_ERR_MEMORY; }
            p->lcap = 16;
        }
        if (!p->edges) { /* (non-NULL: ffc_mortar_links computes the edge points) */
            p->edges = malloc(16 * sizeof *p->edges);
            if (!p->edges) { if (d != p->dual) free(d); return FFC_ERR_MEMORY; }
            p->ecap = 16;
        }
        for (long f = 0; f < p->nfs; f++)
            for (int i = 0; i < 9; i++) d[9 * f + i] = i % 4 == 0;
        p->dual = d;
        p->nl = p->ne = 0;
        p->nq = 0;
        return FFC_OK;
    }
    const int nq = ffc_quad_size(p->o.qdeg);
    ffc_link *links = calloc(p->nfs * nq, sizeof *links);
    if (!links) return FFC_ERR_MEMORY;
    free(p->links);
    p->links = links;
    p->nq = nq;
    p->nl = p->nfs * nq;
    for (long k = 0; k < p->nl; k++) {
        p->links[k].sf = k / p->nq;
        p->links[k].q = (int)(k % p->nq);
        p->links[k].mf = -1;
    }
    return FFC_OK;
}

/* (ffc_scene_state.h) */
int ffc__nts_alloc(const ffc_scene *s, scene_pair *p)
{
    ffc_pair v;
    memset(&v, 0, sizeof v);   /* (obst NULL: node-to-surface pairs have facets on both sides) */
    v.ns = v.nm = s->nper;
    v.nfs = p->nfs;
    v.Fs = p->Fs;
    v.nfm = p->nfm;
    v.Fm = p->Fm;
    v.nv = s->nv;
    v.X = s->X;
    v.u = s->u_prev;
    long need = 0;
    ffc_nts_nodes(&v, 0, NULL, &need);
    if (need <= 0) return FFC_ERR_EMPTY;
    ffc_nts_node *a = calloc(need, sizeof *a), *b = calloc(need, sizeof *b);
    if (!a || !b) { free(a); free(b); return FFC_ERR_MEMORY; }
    long n = ffc_nts_nodes(&v, need, a, &need);
    if (n < 0) { free(a); free(b); return (int)n; }
    memcpy(b, a, n * sizeof *a);
    free(p->nodes);
    free(p->nodes0);
    p->nodes = a;
    p->nodes0 = b;
    p->nn = n;
    p->located = 0;
    memset(&p->nst, 0, sizeof p->nst);
    memset(&p->nst_step, 0, sizeof p->nst_step);
    return FFC_OK;
}

/* a pair of facets Fs on facets Fm, or (ob != NULL, nfm = 0) on a rigid obstacle */
static int pair_add(ffc_scene *s, long nfs, const long Fs[], long nfm, const long Fm[], const ffc_obstacle *ob,
                    const ffc_pair_opts *o, long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (!s || !Fs || (!Fm && !ob) || !o) return FFC_ERR_NULL;
    if (nfs <= 0 || (!ob && nfm <= 0)) return FFC_ERR_EMPTY;
    int st = ffc_pair_opts_check(o);
    if (st) return st;
    if (ob && ((st = ffc_obstacle_check(ob)) || o->method != FFC_METHOD_AL || o->search.self))
        return st ? st : FFC_ERR_VALUE;
    if ((st = check_nodes(nfs * s->nper, Fs, s->nv, bad))) return st;
    if (!ob && (st = check_nodes(nfm * s->nper, Fm, s->nv, bad))) return st;
    if (!ob && o->search.self) { /* self-contact: one surface on both sides */
        if (nfs != nfm || memcmp(Fs, Fm, (size_t)(nfs * s->nper) * sizeof *Fs)) return FFC_ERR_VALUE;
    } else if (!ob && (st = check_fused(s->nper, nfs, Fs, nfm, Fm, s->nv, bad)))
        return st;
    if ((st = check_interior(s, nfs, Fs, nfm, Fm, bad))) return st;
    if ((o->method == FFC_METHOD_NTS || o->dual_t) && s->nper != 3) return FFC_ERR_NODES;
    if (s->np > 0 && s->p[0].o.method != o->method) return FFC_ERR_VALUE; /* one method per scene */
    if (s->np == s->cap) {
        int cap = s->cap ? 2 * s->cap : 4;
        scene_pair *q = realloc(s->p, cap * sizeof *q);
        if (!q) return FFC_ERR_MEMORY;
        s->p = q;
        s->cap = cap;
    }
    scene_pair *p = &s->p[s->np];
    memset(p, 0, sizeof *p);
    p->o = *o;
    p->nfs = nfs;
    p->nfm = ob ? 0 : nfm;
    p->Fs = malloc(nfs * s->nper * sizeof *p->Fs);
    p->Fm = ob ? NULL : malloc(nfm * s->nper * sizeof *p->Fm);
    if (!p->Fs || (!ob && !p->Fm) || pair_alloc_links(p) || pair_alloc_lambda(p, s->nv)) {
        pair_free(p);
        return FFC_ERR_MEMORY;
    }
    memcpy(p->Fs, Fs, nfs * s->nper * sizeof *Fs);
    if (!ob) memcpy(p->Fm, Fm, nfm * s->nper * sizeof *Fm);
    if (ob) {
        p->obst = 1;
        p->ob = p->ob0 = p->base = *ob;
        for (int i = 0; i < 3; i++) p->ob.d[i] = p->ob0.d[i] = p->base.d[i] = p->move[i] = 0.0;
    }
    {
        unsigned char *m = calloc(s->nv, 1);
        if (!m) { pair_free(p); return FFC_ERR_MEMORY; }
        for (long i = 0; i < nfs * s->nper; i++) /* (the multipliers' nodes: the facets' vertices) */
            if (i % s->nper < 3) p->nsn += !m[Fs[i]], m[Fs[i]] = 1;
        free(m);
    }
    if (o->method == FFC_METHOD_NTS && (st = ffc__nts_alloc(s, p))) {
        pair_free(p);
        return st;
    }
    return s->np++;
}

int ffc_scene_add_pair(ffc_scene *s, long nfs, const long Fs[], long nfm, const long Fm[],
                       const ffc_pair_opts *o, long *bad)
{
    if (!Fm) return FFC_ERR_NULL;
    return pair_add(s, nfs, Fs, nfm, Fm, NULL, o, bad);
}

int ffc_scene_add_obstacle(ffc_scene *s, long nfs, const long Fs[], const ffc_obstacle *ob, const ffc_pair_opts *o,
                           long *bad)
{
    if (!ob) return FFC_ERR_NULL;
    return pair_add(s, nfs, Fs, 0, NULL, ob, o, bad);
}

/* (ffc_scene_state.h) */
void ffc__obstacle_motion(const ffc_scene *s, scene_pair *p)
{
    for (int i = 0; i < 3; i++) {
        const double m = p->ob.c[i] - p->ob0.c[i];
        p->ob.d[i] = s->fx.dynamic ? (s->dt > 0 ? m / s->dt : 0.0) : m;
    }
}

int ffc_scene_set_obstacle(ffc_scene *s, int k, const ffc_obstacle *ob, const double move[3])
{
    if (!s || !ob) return FFC_ERR_NULL;
    if (k < 0 || k >= s->np) return FFC_ERR_INDEX;
    scene_pair *p = &s->p[k];
    int st = ffc_obstacle_check(ob);
    if (st) return st;
    if (!p->obst || ob->kind != p->ob.kind) return FFC_ERR_VALUE;
    for (int i = 0; move && i < 3; i++)
        if (!isfinite(move[i])) return FFC_ERR_NONFINITE;
    p->ob = p->base = *ob;
    for (int i = 0; i < 3; i++) p->move[i] = move ? move[i] : 0.0;
    ffc__obstacle_motion(s, p);
    return FFC_OK;
}

int ffc_scene_obstacles_at(ffc_scene *s, double lf)
{
    if (!s) return FFC_ERR_NULL;
    if (!isfinite(lf)) return FFC_ERR_NONFINITE;
    for (int k = 0; k < s->np; k++) {
        scene_pair *p = &s->p[k];
        if (!p->obst) continue;
        for (int i = 0; i < 3; i++) p->ob.c[i] = p->base.c[i] + lf * p->move[i];
        ffc__obstacle_motion(s, p);
    }
    return FFC_OK;
}

int ffc_scene_obstacle_path(const ffc_scene *s, int k, double move[3])
{
    if (!s || !move) return FFC_ERR_NULL;
    if (k < 0 || k >= s->np) return FFC_ERR_INDEX;
    if (!s->p[k].obst) return FFC_ERR_VALUE;
    for (int i = 0; i < 3; i++) move[i] = s->p[k].move[i];
    return FFC_OK;
}

int ffc_scene_obstacle(const ffc_scene *s, int k, ffc_obstacle *ob)
{
    if (!s || !ob) return FFC_ERR_NULL;
    if (k < 0 || k >= s->np) return FFC_ERR_INDEX;
    if (!s->p[k].obst) return FFC_ERR_VALUE;
    *ob = s->p[k].ob;
    return FFC_OK;
}

int ffc_scene_pair_opts(const ffc_scene *s, int k, ffc_pair_opts *o)
{
    if (!s || !o) return FFC_ERR_NULL;
    if (k < 0 || k >= s->np) return FFC_ERR_INDEX;
    *o = s->p[k].o;
    return FFC_OK;
}

int ffc_scene_set_pair_opts(ffc_scene *s, int k, const ffc_pair_opts *o)
{
    if (!s || !o) return FFC_ERR_NULL;
    if (k < 0 || k >= s->np) return FFC_ERR_INDEX;
    int st = ffc_pair_opts_check(o);
    if (st) return st;
    scene_pair *p = &s->p[k];
    if (o->method != p->o.method) return FFC_ERR_VALUE;
    const int relink = o->qdeg != p->o.qdeg, relam = relink || o->nodal != p->o.nodal;
    const ffc_pair_opts old = p->o;
    p->o = *o;
    /* a new rule or multiplier space starts the pair's multipliers afresh
     * (out of memory: the old options, links and multipliers stay) */
    if (relink && (st = pair_alloc_links(p))) { p->o = old; return st; }
    if (relam && (st = pair_alloc_lambda(p, s->nv))) {
        p->o = old;
        if (relink) pair_alloc_links(p); /* back to the old rule's links (smaller or equal: may fail only
                                            where the larger one succeeded) */
        return st;
    }
    return FFC_OK;
}

int ffc_scene_set_fixed(ffc_scene *s, const double fixed[])
{
    if (!s) return FFC_ERR_NULL;
    if (!fixed) {
        free(s->fixed);
        s->fixed = NULL;
        return FFC_OK;
    }
    for (long i = 0; i < 3 * s->nv; i++)
        if (!isfinite(fixed[i])) return FFC_ERR_NONFINITE;
    if (!s->fixed && !(s->fixed = malloc(3 * (size_t)s->nv * sizeof *s->fixed))) return FFC_ERR_MEMORY;
    memcpy(s->fixed, fixed, 3 * (size_t)s->nv * sizeof *fixed);
    return FFC_OK;
}

int ffc_scene_set_motion(ffc_scene *s, const double v[], double dt, double dvdu)
{
    if (!s || !v) return FFC_ERR_NULL;
    if (!s->fx.dynamic) return FFC_ERR_VALUE;
    if (!(dt > 0) || !isfinite(dt) || !finite_nonneg(dvdu)) return FFC_ERR_VALUE;
    for (long i = 0; i < 3 * s->nv; i++)
        if (!isfinite(v[i])) return FFC_ERR_NONFINITE;
    memcpy(s->v, v, 3 * s->nv * sizeof *v);
    s->dt = dt;
    s->dvdu = dvdu;
    for (int k = 0; k < s->np; k++)
        if (s->p[k].obst) ffc__obstacle_motion(s, &s->p[k]);
    return FFC_OK;
}
