/* ffc_pairs.c: mortar pairing: the master facets each slave facet faces and overlaps, and their links. */
#include "ffc.h"
#include "ffc_internal.h"
#include "ffc_tree.h"

#include <math.h>
#include <stdlib.h>

/* Facets (tree slots) whose boxes overlap b[6], into out[cap]; returns
 * their count (may exceed cap: only cap are written). */
static long tree_overlap(const ffc_tree *t, const double b[6], long cap, long out[])
{
    long stack[FFC__STACK], n = 0;
    int sp = 0;
    stack[sp++] = 1;
    while (sp > 0) {
        const long i = stack[--sp];
        const double *c = t->box + 6 * i;
        if (c[0] > b[3] || c[1] > b[4] || c[2] > b[5] || c[3] < b[0] || c[4] < b[1] || c[5] < b[2]) continue;
        if (i >= t->P) {
            const long j = i - t->P;
            for (long s = j * FFC__LEAF; s < (j + 1) * FFC__LEAF && s < t->nf; s++) {
                const double *X = t->fx + s * t->nn * 3;
                double fb[6];
                ffc__facet_box(t->nn, X, fb);
                if (fb[0] > b[3] || fb[1] > b[4] || fb[2] > b[5] || fb[3] < b[0] || fb[4] < b[1] || fb[5] < b[2])
                    continue;
                if (n < cap) out[n] = s;
                n++;
            }
            continue;
        }
        stack[sp++] = 2 * i;
        stack[sp++] = 2 * i + 1;
    }
    return n;
}

/* two facets sharing a corner vertex */
static int share_corner(const long a[], const long b[])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (a[i] == b[j]) return 1;
    return 0;
}

#define MORTAR_PTS 96   /* points of one segment: <= 4 triangles x 12 (degree 6) */
#define MORTAR_CAND 4096 /* master facets overlapping one slave facet's box */

int ffc_mortar_pairs(const ffc_tree *t, long nfs, const long Fs[], long nvs, const double x[],
                     const ffc_search_opts *o, long cap, long pairs[], long *need)
{
    long dummy;
    if (!need) need = &dummy;
    *need = 0;
    if (!t || !Fs || !x || (cap > 0 && !pairs)) return FFC_ERR_NULL;
    const int nn = t->nn; /* (3 or 6: ffc_tree_build) */
    if (nfs <= 0) return FFC_ERR_EMPTY;
    if (cap < 0 || t->nv > nvs) return FFC_ERR_SIZE;
    ffc_search_opts def = ffc_search_defaults();
    if (!o) o = &def;
    if (!(o->capture_rel >= 0) || !(o->capture_abs >= 0) || !(o->edge_tol >= 0) || isinf(o->capture_rel) ||
        isinf(o->capture_abs))
        return FFC_ERR_VALUE;
    for (long k = 0; k < nn * nfs; k++)
        if (Fs[k] < 0 || Fs[k] >= nvs) return FFC_ERR_INDEX;
    for (long k = 0; k < nn * t->nf; k++)
        if (t->F[k] < 0 || t->F[k] >= nvs) return FFC_ERR_INDEX;
    const double rmax = fmax(o->capture_abs, o->capture_rel * t->hmax);
    long n = 0, cand[MORTAR_CAND];
    double xi[MORTAR_PTS][2], w[MORTAR_PTS];
    for (long f = 0; f < nfs; f++) {
        double Xs[FFC_MAXNODES][3], ns[3], box[6]; /* (the segments: the vertex triangles) */
        for (int a = 0; a < nn; a++)
            for (int i = 0; i < 3; i++) {
                Xs[a][i] = x[3 * Fs[nn * f + a] + i];
                if (!isfinite(Xs[a][i])) return FFC_ERR_NONFINITE;
            }
        ffc__tri_normal(Xs[0], Xs[1], Xs[2], ns);
        ffc__facet_box(nn, &Xs[0][0], box);
        for (int i = 0; i < 3; i++) { box[i] -= rmax; box[3 + i] += rmax; }
        const long nc = tree_overlap(t, box, MORTAR_CAND, cand);
        if (nc > MORTAR_CAND) return FFC_ERR_SIZE;
        long nf = 0;
        int captured = 0;
        for (long c = 0; c < nc; c++) {
            const long mf = t->slot2f[cand[c]];
            double Xm[FFC_MAXNODES][3], nm[3];
            for (int a = 0; a < nn; a++)
                for (int i = 0; i < 3; i++) {
                    Xm[a][i] = x[3 * t->F[nn * mf + a] + i];
                    if (!isfinite(Xm[a][i])) return FFC_ERR_NONFINITE;
                }
            ffc__tri_normal(Xm[0], Xm[1], Xm[2], nm);
            if (!(ffc__dot(ns, nm) < 0)) continue; /* not facing */
            /* self-contact (the slave facets are the tree's, in the same order):
               each two facing facets once, from the one of lower index, and
               none sharing a corner with the slave facet (ffc_search_opts) */
            if (o->self && (mf <= f || share_corner(Fs + nn * f, t->F + nn * mf))) continue;
            double cov;
            /* (degree 1: one point per segment triangle, enough for its centre) */
            const int np = ffc_mortar_segment(1, (const double(*)[3])Xs, (const double(*)[3])Xm, MORTAR_PTS, xi, w, 0,
                                              NULL, NULL, NULL, &cov);
            if (np < 0) return np;
            if (np == 0) continue;
            /* capture: the distance from the segment's centre to the master plane */
            double xc[2] = {0, 0}, ws = 0;
            for (int q = 0; q < np; q++) {
                xc[0] += w[q] * xi[q][0];
                xc[1] += w[q] * xi[q][1];
                ws += w[q];
            }
            xc[0] /= ws;
            xc[1] /= ws;
            double pc[3];
            for (int i = 0; i < 3; i++)
                pc[i] = Xs[0][i] + xc[0] * (Xs[1][i] - Xs[0][i]) + xc[1] * (Xs[2][i] - Xs[0][i]);
            ffc_proj pr;
            /* (the vertex triangle's plane: a capture decision, in closed form for 6-node facets too) */
            int st = ffc__project_free(3, (const double(*)[3])Xm, pc, &pr);
            if (st < 0) return st;
            /* a facet within the capture distance of one master facet takes all those it faces and
               overlaps: no facet is cut by the edge of the capture band (its dual basis would be
               that of a part, and move with it) */
            if (fabs(pr.gap) <= fmax(o->capture_abs, o->capture_rel * t->hf[mf])) captured = 1;
            if (n + nf < cap) {
                pairs[2 * (n + nf)] = f;
                pairs[2 * (n + nf) + 1] = mf;
            }
            nf++;
        }
        if (captured) n += nf;
    }
    *need = n;
    return n > cap ? FFC_ERR_CAPACITY : (n <= 2147483647L ? (int)n : FFC_ERR_SIZE);
}

int ffc_mortar_search(const ffc_tree *t, long nfs, const long Fs[], long nvs, const double x[], int qdeg,
                      const ffc_search_opts *o, long cap, ffc_link links[], long *need)
{
    long dummy;
    if (!need) need = &dummy;
    *need = 0;
    if (!t || !Fs || !x || (cap > 0 && !links)) return FFC_ERR_NULL;
    if (ffc_quad_size(qdeg) < 0) return FFC_ERR_QUAD;
    long np = 0;
    int st = ffc_mortar_pairs(t, nfs, Fs, nvs, x, o, 0, NULL, &np);
    if (st < 0 && st != FFC_ERR_CAPACITY) return st;
    long *pairs = malloc((size_t)(2 * np + 2) * sizeof *pairs);
    if (!pairs) return FFC_ERR_MEMORY;
    st = ffc_mortar_pairs(t, nfs, Fs, nvs, x, o, np, pairs, &np);
    if (st >= 0) st = ffc_mortar_links(t->nn, nfs, Fs, t->nf, t->F, nvs, x, qdeg, np, pairs, cap, links, need, 0, NULL, NULL);
    free(pairs);
    return st;
}
