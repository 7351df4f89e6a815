/* ffc_internal.h: small vector helpers and constants shared by the kernels
 * (not part of the public interface). */
#ifndef FFC_INTERNAL_H
#define FFC_INTERNAL_H

#include <math.h>

/* A facet is degenerate when its area element is below this fraction of
 * its squared size (a sliver with angles below ~1e-10 rad). */
#define FFC__DEGEN_REL 1e-12

/* a linear facet with |t0 x t1|^2 = c2 and squared size h2 is degenerate */
static inline int ffc__degenerate(double c2, double h2)
{
    return !(c2 > FFC__DEGEN_REL * FFC__DEGEN_REL * h2 * h2);
}

/* qsort's comparison of longs, ascending */
static inline int ffc__cmp_long(const void *a, const void *b)
{
    const long x = *(const long *)a, y = *(const long *)b;
    return (x > y) - (x < y);
}

/* how far the local coordinates xi lie outside the reference triangle (0 inside) */
static inline double ffc__outside(const double xi[2])
{
    return fmax(0.0, fmax(-xi[0], fmax(-xi[1], xi[0] + xi[1] - 1.0)));
}

static inline double ffc__dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void ffc__cross(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* a triangle's normal (b - a) x (c - a), not scaled: twice its area */
static inline void ffc__tri_normal(const double a[3], const double b[3], const double c[3], double n[3])
{
    const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    ffc__cross(e1, e2, n);
}

double ffc__facet_size2(const double X[][3]);

#include "ffc.h"
/* Foot on the facet's extension (no clamping): xi = xi_free; _from starts
 * a curved facet's Newton iteration at xi0 (a foot of the same point
 * found before) instead of the vertex triangle's solution (xi0 NULL: the
 * same as ffc__project_free; straight facets: closed form, xi0 unused). */
int ffc__project_free(int nn, const double X[][3], const double p[3], ffc_proj *out);
int ffc__project_free_from(int nn, const double X[][3], const double p[3], const double xi0[2], ffc_proj *out);

/* LU with partial pivoting of the column-major A[m*m] in place, then b =
 * A^-1 b (LAPACK); piv[m] work.  FFC_ERR_SINGULAR for a pivot below 1e-15
 * of the largest entry, FFC_ERR_NONFINITE for a non-finite entry
 * (ffc_reduced.c). */
int ffc__lu_solve(long m, double A[], long piv[], double b[]);
/* FFC_ERR_INDEX / FFC_ERR_NONFINITE (*bad = the triplet) for an index
 * outside [0, n) or a non-finite value among (Ti, Tj, Tv)[nt], else FFC_OK */
int ffc__check_triplets(long n, long nt, const long Ti[], const long Tj[], const double Tv[], long *bad);

/* the corner of link lk's slave facet nearest its point (the largest
 * linear shape value) among those whose state[3] (FFC_FRIC_*) is not
 * open; -1: all open */
int ffc__nearest_corner(const ffc_link *lk, const int state[3]);

/* ffc_augment with, where state is not NULL, each multiplier's friction
 * state as its update found it (FFC_FRIC_*: state[v] per slave node v of
 * the nodal law, state[k] per link otherwise): slip where the trial
 * traction left the Coulomb cone; open throughout without friction */
int ffc__augment(const ffc_effects *effects, const ffc_pair *pair, int qdeg, long nl, const ffc_link links[],
                 double lambda[], double lam_t[], const ffc_law *law, ffc_stats *stats, signed char state[],
                 long *bad);

/* GMRES's Hessenberg column h[j + 2] (modified Gram-Schmidt's) turned
 * upper triangular: the earlier rotations (cs, sn)[j] applied, the new
 * one made and applied to it and to the residual vector g (g[j + 1] is
 * then the residual's norm, with its sign); -1 for a zero column */
static inline int ffc__gmres_rotate(long j, double h[], double cs[], double sn[], double g[])
{
    for (long i = 0; i < j; i++) {
        const double hi = cs[i] * h[i] + sn[i] * h[i + 1];
        h[i + 1] = -sn[i] * h[i] + cs[i] * h[i + 1];
        h[i] = hi;
    }
    const double rr = hypot(h[j], h[j + 1]);
    if (!(rr > 0.0)) return -1;
    cs[j] = h[j] / rr;
    sn[j] = h[j + 1] / rr;
    h[j] = rr;
    h[j + 1] = 0.0;
    g[j + 1] = -sn[j] * g[j];
    g[j] *= cs[j];
    return 0;
}

/* Straight-sided tetrahedra (ffc_tet.c).  FreeFEM's edge order of a P2
 * tetrahedron's nodes 4..9: 01 02 03 12 13 23. */
extern const int ffc__tet_edge[6][2];
/* the position of j in the ascending list c[n] (present by construction) */
long ffc__find_long(const long c[], long n, long j);
/* The node graph of the tetrahedra's nodes E[nt*npe] (nn nodes): row i
 * lists i and the nodes that share a tetrahedron with it, ascending, each
 * once, in adj[rp[i] .. rp[i] + fill[i]) (rp[nn]: their count, returned).
 * Sizes: rp[nn + 1], fill[nn + 1], adj[npe (npe - 1) nt + nn + 1] (the
 * rows are compacted in place). */
long ffc__tet_graph(long nt, long npe, long nn, const long E[], long rp[], long adj[], long fill[]);
/* Tetrahedron v[4]'s barycentric gradients g (g[0] = -(g[1] + g[2] +
 * g[3])) and volume *V; FFC_ERR_DEGENERATE for a zero volume (|det J| <=
 * 1e-13 |e1| |e2| |e3|) */
int ffc__tet_gradients(const double X[], const long v[4], double g[4][3], double *V);
/* The gradients G[npe] of the shape functions at the barycentric point L
 * (npe 4: the g themselves; 10: N_a = L_a (2 L_a - 1) at the vertices, 4
 * L_p L_q on edge pq) */
void ffc__tet_shape_gradients(long npe, const double g[4][3], const double L[4], double G[10][3]);
/* The 14-point rule of degree 5 (FreeFEM's qfV5): points L, weights w as
 * fractions of the volume; returns 14 */
int ffc__tet_rule5(double L[14][4], double w[14]);

/* Six times the signed volume of each tetrahedron T[nt*4] at X (v0[nt]),
 * and ffc_volume_check against them (corner indices already checked):
 * the reference volumes computed once instead of at each check. */
void ffc__tet_volumes(long nt, const long T[], const double X[], double v0[]);
int ffc__volume_check_ref(long nt, const long T[], const double X[], const double v0[], const double u[], long *bad);

/* The dual basis of a linear slave facet from its covered part
 * (ffc_mortar.c, see ffc_dual_basis): the moments c = sum_q w_q,
 * D_a = sum_q w_q N_a, M_ab = sum_q w_q N_a N_b of its points, */
typedef struct {
    double c, D[3], M[3][3];
} ffc__dual_moments;
/* a point added to them, */
void ffc__dual_add(ffc__dual_moments *m, const double xi[2], double w);
/* the blend s of the dual basis and M^-1 into Mi (s = 0: the standard
 * basis, for a coverage below half or a nearly singular M), */
double ffc__dual_blend(const ffc__dual_moments *m, double Mi[3][3]);
/* and A = s D M^-1 + (1 - s) I. */
void ffc__dual_matrix(const ffc__dual_moments *m, double A[3][3]);

/* The ranks of a communicator (its Fortran handle fcomm; ffc_mpi.c): this
 * process's rank and their count (0 and 1 without MPI or before MPI_Init);
 * the smallest of every rank's v (a collective call: the ranks agree on
 * a branch); and an all-gather in place: rank r's count[r] doubles sit in
 * buf after those of the ranks before it, and every rank receives all. */
int ffc__mpi_ranks(int fcomm, int *rank, int *size);
int ffc__mpi_min(int fcomm, int v);
int ffc__mpi_allgather(int fcomm, double buf[], const long count[]);
/* a monotonic clock (seconds) */
double ffc__seconds(void);

#endif
