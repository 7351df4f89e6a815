/* ffc_scene.c: a contact scene: the nodes of one mesh and any number of
 * contact pairs, each owning its facets, search tree, links, multipliers,
 * checkpoint and statistics; search, assembly, augmentation and output
 * over all pairs. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ffc.h"
#include "ffc_bulk.h"
#include "ffc_internal.h"

typedef struct {
    ffc_pair_opts o;   /* method, law and search options */
    long nfs, nfm;     /* slave, master facets */
    long *Fs, *Fm;     /* [nfs*nper], [nfm*nper] facet nodes */
    ffc_tree *tree;    /* over the master facets (built at the first search) */
    int nq;            /* quadrature points per slave facet */
    long nl;           /* links: nfs * nq (mortar: as the last search found) */
    long lcap;         /* capacity of links (mortar) */
    long nsn;          /* distinct slave nodes (mortar: its output rows) */
    long *mp, nmp, mpcap; /* mortar: the facet pairs of the last search [2 mpcap], their count */
    ffc_mortar_edge *edges; /* [ecap] mortar: the moving-edge points of the segments */
    long ne, ecap;
    ffc_link *links;   /* [nl] */
    double *dual;      /* [9 nfs] mortar: the dual basis of each slave facet (ffc_dual_basis) */
    long nlam;         /* multipliers: nv (nodal) or nl (pointwise) */
    double *lam, *lam_t;   /* [nlam], [3 nlam] */
    double *lam0, *lam_t0; /* the same at the last commit */
    ffc_stats st;      /* last assembly, with the augmentation's own fields
                          (max_dlam, max_dlam_t, max_pen_node) of the last augmentation */
    ffc_stats st_step; /* st at the last commit: the converged step's statistics */
    /* node-to-surface (o.method == FFC_METHOD_NTS) */
    long nn;           /* slave nodes */
    ffc_nts_node *nodes, *nodes0; /* [nn] their table, and at the last commit */
    int located;       /* 1 once the nodes were located (their states set) */
    long row0, nr;     /* its rows in the stacked rows of the last ffc_scene_nts_rows */
    ffc_nts_stats nst, nst_step; /* the last update, and at the last commit */
} scene_pair;

struct ffc_scene {
    int nper;          /* nodes per facet: 3 (linear) or 6 (quadratic) */
    long nv;           /* nodes */
    double *X;         /* [nv*3] reference positions (length) */
    long nt;           /* tetrahedra (for the inversion check; 0: none) */
    long *T;           /* [nt*4] corner nodes of each tetrahedron */
    double *v0;        /* [nt] six times each one's reference volume (length^3) */
    ffc_effects fx;    /* the scene's effects (friction: per pair, mu > 0) */
    double *u_prev;    /* [nv*3] displacement at the last commit (length) */
    double *v;         /* [nv*3] velocities (dynamic; length/time) */
    double dt, dvdu;   /* dynamic: time step (time), dv/du (1/time) */
    double *x;         /* [nv*3] work: current positions */
    int np, cap;       /* pairs, capacity */
    scene_pair *p;     /* [cap] */
    ffc__bulk *bulk;   /* the bulk factorization (NULL: none set) */
    ffc_parallel par;  /* where the bulk matrix is factorized */
    double *fixed;     /* [nv*3] prescribed dofs (nonzero), or NULL: none given */
    ffc_settings set;  /* the driver's settings */
    ffc_bulk_law law;  /* what the bulk is (its kind, linear, symmetric, finite deformation) */
    ffc_linesearch ls; /* the driver's Newton line search in progress */
};

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
        !finite_nonneg(o->search.edge_tol))
        return FFC_ERR_VALUE;
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
    case FFC_BULK_USER: return (ffc_bulk_law){FFC_BULK_USER, 0, 1, 0};
    default: return (ffc_bulk_law){FFC_BULK_LINEAR, 1, 1, 0};
    }
}

int ffc_scene_set_law(ffc_scene *s, const ffc_bulk_law *law)
{
    if (!s || !law) return FFC_ERR_NULL;
    if ((law->kind != FFC_BULK_LINEAR && law->kind != FFC_BULK_NEOHOOKEAN && law->kind != FFC_BULK_USER) ||
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
    if (!l || !l0 || !lt || !lt0) {
        free(l); free(l0); free(lt); free(lt0);
        return FFC_ERR_MEMORY;
    }
    free(p->lam); free(p->lam_t); free(p->lam0); free(p->lam_t0);
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

/* The slave node table of a node-to-surface pair, every node open and
 * not located (and its checkpoint); on failure the pair keeps its own. */
static int nts_alloc(const ffc_scene *s, scene_pair *p)
{
    ffc_pair v;
    memset(&v, 0, sizeof v);
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

int ffc_scene_add_pair(ffc_scene *s, long nfs, const long Fs[], long nfm, const long Fm[],
                       const ffc_pair_opts *o, long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (!s || !Fs || !Fm || !o) return FFC_ERR_NULL;
    if (nfs <= 0 || nfm <= 0) return FFC_ERR_EMPTY;
    int st = ffc_pair_opts_check(o);
    if (st) return st;
    if ((st = check_nodes(nfs * s->nper, Fs, s->nv, bad))) return st;
    if ((st = check_nodes(nfm * s->nper, Fm, s->nv, bad))) return st;
    if ((st = check_fused(s->nper, nfs, Fs, nfm, Fm, s->nv, bad))) return st;
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
    p->nfm = nfm;
    p->Fs = malloc(nfs * s->nper * sizeof *p->Fs);
    p->Fm = malloc(nfm * s->nper * sizeof *p->Fm);
    if (!p->Fs || !p->Fm || pair_alloc_links(p) || pair_alloc_lambda(p, s->nv)) {
        pair_free(p);
        return FFC_ERR_MEMORY;
    }
    memcpy(p->Fs, Fs, nfs * s->nper * sizeof *Fs);
    memcpy(p->Fm, Fm, nfm * s->nper * sizeof *Fm);
    if (o->method == FFC_METHOD_MORTAR) {
        unsigned char *m = calloc(s->nv, 1);
        if (!m) { pair_free(p); return FFC_ERR_MEMORY; }
        for (long i = 0; i < nfs * s->nper; i++) /* (the multipliers' nodes: the facets' vertices) */
            if (i % s->nper < 3) p->nsn += !m[Fs[i]], m[Fs[i]] = 1;
        free(m);
    }
    if (o->method == FFC_METHOD_NTS && (st = nts_alloc(s, p))) {
        pair_free(p);
        return st;
    }
    return s->np++;
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
    return FFC_OK;
}

/* Current positions x = X + u; FFC_ERR_NONFINITE (*bad = node) otherwise. */
static int positions(ffc_scene *s, const double u[], long *bad)
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
    int st = positions(s, u, bad);
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
    int st = positions(s, u, bad);
    if (st) return st;
    long total = 0;
    for (int k = 0; k < s->np; k++) {
        scene_pair *p = &s->p[k];
        if (p->o.method == FFC_METHOD_NTS) continue; /* its nodes are located by ffc_scene_nts_rows */
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

/* The rule the kernels take: the pair's, or 0 for segment links */
static int pair_qdeg(const scene_pair *p) { return p->o.method == FFC_METHOD_MORTAR ? 0 : p->o.qdeg; }

/* What the kernels take for one pair: its nodes, its law, its effects. */
typedef struct {
    ffc_pair v;
    ffc_law law;
    ffc_effects fx;
} pair_call;

/* The kernels' view of pair p at displacement u, and its law. */
static pair_call pair_view(const ffc_scene *s, const scene_pair *p, const double u[], int tangent)
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
    memset(law, 0, sizeof *law);
    law->eps_n = p->o.eps_n;
    law->nodal = p->o.nodal;
    law->material_only = tangent == FFC_TANGENT_MATERIAL ? 1 : tangent == FFC_TANGENT_RANKED ? 2 : 0;
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

/* 1 when every pair has its normal penalty; else 0 with *bad = the first
 * pair without one. */
static int penalties_set(const ffc_scene *s, long *bad)
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

/* The ranks of a communicator sharing out a pair's links (the condensed
 * Newton's contact evaluations on several ranks): rank r takes the linked
 * links [n r / size, n (r + 1) / size) of the n in the links' order (by
 * slave facet: a share is a strip of slave facets); the node sums,
 * the residual at the pair's dofs, the triplets and the link statistics
 * are summed over the ranks in rank order, so that every rank gets the
 * same bits.  Every call below is collective: each rank makes the same
 * ones, also on failure (the first failing rank's status is every rank's). */
typedef struct {
    int comm, rank, size;
} share_ctx;

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
        for (int a = 0; a < 2 * s->nper; a++) {
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
        st = ffc_assemble(fx, v, pair_qdeg(p), p->nl, p->links, p->lam, p->lam_t, &law, Rp, room, Ti, Tj, Tv, &nloc,
                          &p->st, bad);
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
    if (!gs && (!g || g == FFC_ERR_CAPACITY)) {
        double *sb = malloc(10 * (size_t)c->size * sizeof *sb);
        if (!ffc__mpi_min(c->comm, sb != NULL)) gs = FFC_ERR_MEMORY;
        else {
            double *q = sb + 10 * c->rank;
            q[0] = (double)p->st.linked; q[1] = (double)p->st.active;
            for (int i = 0; i < 3; i++) { q[2 + i] = p->st.force[i]; q[5 + i] = p->st.force_t[i]; }
            q[8] = p->st.max_pen; q[9] = p->st.max_tn;
            for (int r = 0; r < c->size; r++) cnt[r] = 10;
            gs = ffc__mpi_allgather(c->comm, sb, cnt);
            if (!gs) {
                ffc_stats *t = &p->st;
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
    }
    free(all);
    free(cnt);
    free(hd);
    free(sel);
    free(nodes);
    free(Rp);
    return g ? g : gs;
}

static int scene_assemble(ffc_scene *s, const double u[], int tangent, double R[], long cap, long Ti[], long Tj[],
                          double Tv[], long *ntrip, long *bad, const share_ctx *share, int *shared);

int ffc_scene_assemble(ffc_scene *s, const double u[], int tangent, double R[], long cap, long Ti[], long Tj[],
                       double Tv[], long *ntrip, long *bad)
{
    return scene_assemble(s, u, tangent, R, cap, Ti, Tj, Tv, ntrip, bad, NULL, NULL);
}

/* ffc_scene_assemble; with share (not NULL), the augmented Lagrangian's
 * nodal pairs without segments share out their links over its ranks
 * where the tangent is none or ranked (the others evaluate whole on every
 * rank) */
static int scene_assemble(ffc_scene *s, const double u[], int tangent, double R[], long cap, long Ti[], long Tj[],
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
    if (!penalties_set(s, bad)) return FFC_ERR_VALUE;
    int fs = mortar_follow(s, u, tangent == FFC_TANGENT_CONSISTENT, bad); /* the mortar segments at u */
    if (fs) return fs;
    long nt = 0, nterm = 0; /* (ranked: the terms of the pairs before) */
    int over = 0;
    for (int k = 0; k < s->np; k++) {
        scene_pair *p = &s->p[k];
        if (p->o.method == FFC_METHOD_NTS) continue; /* constraint rows instead: ffc_scene_nts_rows */
        const pair_call c = pair_view(s, p, u, tangent);
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
                        : ffc_assemble(&c.fx, &c.v, pair_qdeg(p), p->nl, p->links, p->lam, p->lam_t, &c.law, R, room,
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
    if (!penalties_set(s, bad)) return FFC_ERR_VALUE;
    int fs = mortar_follow(s, u, 0, bad); /* the mortar segments at u */
    if (fs) return fs;
    for (int k = 0; k < s->np; k++) {
        scene_pair *p = &s->p[k];
        if (p->o.method == FFC_METHOD_NTS) continue;
        const pair_call c = pair_view(s, p, u, FFC_TANGENT_NONE);
        int st = ffc_augment(&c.fx, &c.v, pair_qdeg(p), p->nl, p->links, p->lam, p->lam_t, &c.law, &p->st, bad);
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
        p->st_step = p->st;
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
        memset(&p->st, 0, sizeof p->st);
        memset(&p->st_step, 0, sizeof p->st_step);
        for (long l = 0; l < p->nl; l++) p->links[l].mf = -1;
        if (p->o.method == FFC_METHOD_MORTAR) p->nl = p->ne = p->nmp = 0;
        if (p->nodes) {
            int st = nts_alloc(s, p);
            if (st) return st;
        }
    }
    return FFC_OK;
}

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

long ffc_scene_npoints(const ffc_scene *s, int pair)
{
    if (!s) return FFC_ERR_NULL;
    if (pair < -1 || pair >= s->np) return FFC_ERR_INDEX;
    long n = 0;
    for (int k = 0; k < s->np; k++)
        if (pair < 0 || k == pair)
            n += s->p[k].o.method == FFC_METHOD_NTS ? s->p[k].nn : s->p[k].o.method == FFC_METHOD_MORTAR ? s->p[k].nsn : s->p[k].nl;
    return n;
}

int ffc_scene_points(const ffc_scene *s, const double u[], int pair, long cap, double P[], long *n, long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (!s || !u || !P || !n) return FFC_ERR_NULL;
    const long need = ffc_scene_npoints(s, pair);
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
        const pair_call c = pair_view(s, p, u, FFC_TANGENT_NONE);
        if (p->o.method == FFC_METHOD_MORTAR) {
            long got;
            int st = ffc_points_nodes(&c.fx, &c.v, 0, p->nl, p->links, p->lam, p->lam_t, &c.law, p->nsn,
                                      P + row * FFC_POINT_COLS, &got, bad);
            if (st) return st;
            row += p->nsn;
            continue;
        }
        int st = ffc_points(&c.fx, &c.v, pair_qdeg(p), p->nl, p->links, p->lam, p->lam_t, &c.law,
                            P + row * FFC_POINT_COLS, bad);
        if (st) return st;
        row += p->nl;
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

/* mean longest edge (vertices 0-2) of nf facets F[nf*nper] at positions X */
static double mean_size(int nper, long nf, const long F[], const double X[])
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
        const double hs = mean_size(s->nper, p->nfs, p->Fs, s->X), hm = mean_size(s->nper, p->nfm, p->Fm, s->X);
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
        const double h = mean_size(nper, 1, F + nper * f, X);
        if (!(Ep[f] > 0) || !isfinite(Ep[f])) return FFC_ERR_VALUE;
        if (!(h > 0)) return FFC_ERR_DEGENERATE;
        sum += Ep[f] / h;
    }
    *k = sum / nf;
    return FFC_OK;
}

int ffc_scene_auto_penalty(const ffc_scene *s, int pair, const double Ep_s[], const double Ep_m[], double *eps)
{
    if (!s || !Ep_s || !Ep_m || !eps) return FFC_ERR_NULL;
    if (pair < 0 || pair >= s->np) return FFC_ERR_INDEX;
    const scene_pair *p = &s->p[pair];
    double ks, km;
    int st = side_stiffness(s->nper, p->nfs, p->Fs, s->X, Ep_s, &ks);
    if (!st) st = side_stiffness(s->nper, p->nfm, p->Fm, s->X, Ep_m, &km);
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
    return ffc__bulk_solve(s->bulk, nt, Ti, Tj, Tv, b, x, bad);
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
                              : 1e-11 * fmin(mean_size(s->nper, p->nfs, p->Fs, s->X), mean_size(s->nper, p->nfm, p->Fm, s->X));
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
    int st = positions(s, u, bad);
    if (st) return st;
    const long n = 3 * s->nv;
    long nt = 0, nr = 0;
    int over = 0;
    for (int k = 0; k < s->np; k++) {
        scene_pair *p = &s->p[k];
        if (p->o.method != FFC_METHOD_NTS) continue;
        ffc_nts_law law;
        if ((st = nts_law(s, p, &law))) { *bad = k; return st; }
        const pair_call pc = pair_view(s, p, u, FFC_TANGENT_NONE);
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
    if (!st) st = ffc__bulk_saddle(s->bulk, nt, Bi, Bj, Bv, Fv, nr, c, rhs, x, m, bad);
    free(Bi); free(Bj); free(Bv); free(Fv); free(c);
    return st;
}

int ffc_scene_nts_update(ffc_scene *s, const double u[], long nrows, const double m[], long *changes, long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (!s || !u || !changes || (nrows > 0 && !m)) return FFC_ERR_NULL;
    int st = positions(s, u, bad);
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
        const pair_call pc = pair_view(s, p, u, FFC_TANGENT_NONE);
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
    const int st = scene_assemble(c->s, u, tangent, R, cap, Ti, Tj, Tv, nt, bad, c->share, &any);
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
    if (!penalties_set(s, bad)) return FFC_ERR_VALUE;
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
            for (int side = 0; side < 2; side++) {
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
