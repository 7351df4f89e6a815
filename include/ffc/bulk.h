/* ffc/bulk.h: the bulk: contact-reduced solve, sparse triplets, elasticity, mass redistribution, P2 tetrahedra. */
#ifndef FFC_API_BULK_H
#define FFC_API_BULK_H

#include "status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------- contact-reduced linear solve */
/* Formulation.  In a small-strain quasi-static scene the bulk stiffness K
 * (n x n, symmetric, Dirichlet rows included) does not change: it is
 * factorized once, and the contact tangent Kc, which touches only the m
 * contact dofs C (Kc = P Kcc P^T, P the n x m selection), is handled on
 * those dofs.  With G = P^T K^-1 P (m x m, the compliance of the contact
 * dofs; column j is K^-1 e_dof[j] at the contact dofs, one back-solve) and
 * y = K^-1 b:
 *     (K + P Kcc P^T) x = b   <=>   (I + G Kcc) x_C = y_C,
 *                                   x = y - K^-1 P (Kcc x_C),
 * so a Newton iteration costs two back-solves with K and one dense m x m
 * solve instead of a factorization of K + Kc.  G only grows: a dof that
 * Kc touches for the first time adds one column (and, K being symmetric,
 * the same row).  Kcc may be non-symmetric (friction).  A body held only
 * by contact makes K singular: then K + S is factorized instead, S = diag(sh)
 * non-zero only on contact dofs, and Kcc - S_CC takes Kcc's place (exact:
 * K + Kc = (K + S) + P (Kcc - S_CC) P^T). */

/* The dofs that the triplets (Ti, Tj, Tv)[nt] of an n x n matrix touch
 * with a non-zero value (row or column) and that are not among dof[m]:
 * written to out[cap] in ascending order, *nout their count (or the count
 * needed, with FFC_ERR_CAPACITY).  pos[n] is work space (on return all -1).
 * FFC_ERR_INDEX when an index is outside [0, n). */
int ffc_reduced_missing(long n, long m, const long dof[], long nt, const long Ti[], const long Tj[],
                        const double Tv[], long cap, long out[], long *nout, long pos[]);

/* Appends the dof j to dof[m] (capacity ld) and the column x[n] = K^-1 e_j
 * to G (column-major, leading dimension ld): G(i, m) = G(m, i) = x[dof[i]]
 * for i < m, G(m, m) = x[j].  FFC_ERR_CAPACITY when m >= ld, FFC_ERR_INDEX
 * for j outside [0, n) or already in dof[], FFC_ERR_NONFINITE for a
 * non-finite x at the contact dofs. */
int ffc_reduced_add(long n, long ld, long m, long dof[], double G[], const double x[], long j);

/* Solves (I + G Kcc') x_C = y_C with Kcc' = Kcc - diag(sh) at the contact
 * dofs (sh[n] may be NULL: no shift), Kcc from the triplets (Ti, Tj,
 * Tv)[nt] (global dofs, each in dof[m]), and writes w[n] = P (Kcc' x_C)
 * (zero off the contact dofs); xc[m] receives x_C.  Work: A[m*m], piv[m],
 * pos[n] (on return all -1).  FFC_ERR_INDEX when a triplet or a non-zero
 * shift touches a dof outside dof[] (call ffc_reduced_missing / _add
 * first), FFC_ERR_SINGULAR on a zero pivot, FFC_ERR_NONFINITE for
 * non-finite input. */
int ffc_reduced_solve(long n, long ld, long m, const long dof[], const double G[], long nt, const long Ti[],
                      const long Tj[], const double Tv[], const double sh[], const double y[], double xc[],
                      double w[], double A[], long piv[], long pos[]);

/* -------------------------------------------------------- sparse triplets */
/* Sums the duplicates of the triplets (Ti, Tj, Tv)[nt] of an n x n matrix
 * into (Ci, Cj, Cv) (capacity nt: the sum never has more), grouped by row
 * in ascending order, columns within a row in order of first appearance;
 * returns the number of distinct entries.  Work: rp[n + 1], w[n].  The
 * contact tangent of the nodal law repeats entries about 12 times (Hertz):
 * summing them here hands FreeFEM a matrix, not a list to hash.
 * FFC_ERR_INDEX for an index outside [0, n). */
long ffc_triplets_sum(long n, long nt, const long Ti[], const long Tj[], const double Tv[], long Ci[],
                      long Cj[], double Cv[], long rp[], long w[]);

/* ------------------------------------------------ linear elasticity */
/* The stiffness matrix of isotropic linear elasticity on linear
 * tetrahedra: int lambda div u div v + 2 mu eps(u) : eps(v), for the
 * displacement field [P1, P1, P1] whose dof 3 i + c is component c of
 * vertex i (nv vertices X[3 nv]; nt tetrahedra T[4 nt]; Lame's lambda
 * lam[nt] and mu mu[nt], constant per tetrahedron).  Its distinct entries
 * go to (Ki, Kj, Kv)[cap], *nnz of them: row by row (ascending), columns
 * ascending within a row, both triangles (the matrix is symmetric); the
 * count needed is 9 x (vertex pairs that share a tetrahedron, each vertex
 * with itself included), *nnz with FFC_ERR_CAPACITY.  FFC_ERR_INDEX for a
 * vertex index outside [0, nv), FFC_ERR_NONFINITE for a coordinate (*bad =
 * the vertex) or a Lame constant (*bad = the tetrahedron) that is NaN or
 * Inf, FFC_ERR_DEGENERATE for a tetrahedron of zero volume (|det J| <=
 * 1e-13 |e1| |e2| |e3|, J = [e1 e2 e3] its edges from the first vertex;
 * *bad = it). */
int ffc_elastic_p1(long nv, const double X[], long nt, const long T[], const double lam[], const double mu[],
                   long cap, long Ki[], long Kj[], double Kv[], long *nnz, long *bad);

/* The same on quadratic tetrahedra ([P2, P2, P2], straight-sided: the
 * geometry from the vertices X, T): nn nodes, node[10 nt] each
 * tetrahedron's nodes in FreeFEM's order (ffc_p2_number: the vertices,
 * then the edges 01 02 03 12 13 23), dof 3 i + c of node i; the count
 * needed is 9 x (node pairs that share a tetrahedron, each node with
 * itself); FFC_ERR_INDEX also for a node outside [0, nn). */
int ffc_elastic_p2(long nv, const double X[], long nt, const long T[], long nn, const long node[],
                   const double lam[], const double mu[], long cap, long Ki[], long Kj[], double Kv[], long *nnz,
                   long *bad);

/* ------------------------------------------------ hyperelasticity */
/* A volume mesh of straight-sided tetrahedra and the nodes of its
 * displacement field (dof 3 i + c: component c of node i). */
typedef struct {
    long nv;          /* vertices */
    const double *X;  /* [3 nv] their coordinates */
    long nt;          /* tetrahedra */
    const long *T;    /* [4 nt] their vertices */
    long npe;         /* nodes per tetrahedron: 4 (P1) or 10 (P2, FreeFEM's order: vertices, edges 01 02 03 12 13 23) */
    long nn;          /* nodes of the displacement field */
    const long *E;    /* [npe nt] each tetrahedron's nodes (P1: T itself) */
} ffc_tets;

/* The hyperelastic laws, each of Lame's lambda and mu (its linearization
 * at F = I is linear elasticity of the same constants). */
enum {
    FFC_HYPER_NEOHOOKEAN = 1, /* W = mu/2 (F:F - 3) - mu ln J + lambda/2 (ln J)^2 (J = det F > 0) */
    FFC_HYPER_SVK = 2,        /* Saint Venant-Kirchhoff: W = lambda/2 (tr E)^2 + mu E:E, E = (F^T F - I)/2 */
    FFC_HYPER_MOONEYRIVLIN = 3 /* W = c10 (I1 - 3) + c01 (I2 - 3) - 2 (c10 + 2 c01) ln J + lambda'/2 (ln J)^2,
                                  c10 = mu/2 - c01, lambda' = lambda - 4 c01, 0 <= c01 <= mu/2 (J > 0) */
};

/* The pointwise law at the deformation gradient F[9] (row-major, F_iJ at
 * 3 i + J): the energy density *W, the first Piola-Kirchhoff stress P[9]
 * and, unless A is NULL, its derivative A[81] = dP_iJ / dF_kL at 27 i + 9
 * J + 3 k + L; c01 is the Mooney-Rivlin law's second constant (the other
 * laws ignore it).  FFC_ERR_INVERTED for the Neo-Hookean and Mooney-Rivlin
 * laws at det F <= 0, FFC_ERR_VALUE for an unknown law or c01 outside
 * [0, mu / 2]. */
int ffc_hyper_point(int law, double lam, double mu, double c01, const double F[9], double *W, double P[9], double A[81]);

/* The node graph of the mesh's nodes: row i lists node i and the nodes
 * that share a tetrahedron with it, ascending, in adj[rp[i] .. rp[i + 1])
 * (rp[nn + 1]; adj[cap], *nb entries needed, FFC_ERR_CAPACITY when cap is
 * smaller).  The matrices of the operators below have 9 *nb entries: dof
 * row 3 i + c holds 3 (rp[i + 1] - rp[i]) of them from 9 rp[i] + 3 c
 * (rp[i + 1] - rp[i]), their columns ascending (ffc_tets_pattern_ij
 * writes each entry's row and column). */
int ffc_tets_pattern(const ffc_tets *m, long cap, long rp[], long adj[], long *nb, ffc_error *err);
void ffc_tets_pattern_ij(long nn, const long rp[], const long adj[], long Ki[], long Kj[]);

/* The hyperelastic operator at the displacement u[3 nn], total
 * Lagrangian on the reference mesh m: the stored energy *W, the internal
 * force f[3 nn] (int P : grad v) and its tangent Kv[9 rp[nn]] on the
 * pattern (rp, adj) of ffc_tets_pattern; any of W, f, Kv may be NULL
 * (not computed).  Lame's constants lam[nt], mu[nt] per tetrahedron (the
 * linearization's), and the Mooney-Rivlin law's c01[nt] (NULL for the others).
 * Quadrature: one point on P1 (F is constant), FreeFEM's qfV5 (14 points,
 * degree 5) on P2.  Errors (err: the tetrahedron, dof or node):
 * FFC_ERR_INVERTED (det F <= 0 at a point of the Neo-Hookean or Mooney-Rivlin law),
 * FFC_ERR_DEGENERATE (a tetrahedron of no volume), FFC_ERR_NONFINITE,
 * FFC_ERR_INDEX (a node outside the mesh or the pattern), FFC_ERR_VALUE
 * (an unknown law, a c01 outside [0, mu / 2]). */
int ffc_hyper_assemble(int law, const ffc_tets *m, const double lam[], const double mu[], const double c01[],
                       const double u[], const long rp[], const long adj[], double *W, double f[], double Kv[],
                       ffc_error *err);

/* ------------------------------------------------ mass redistribution */
/* The interpolation T (n x n) of a redistributed mass M_red = T' M T for
 * contact dynamics: row i is e_i for a dof off the contact surfaces
 * (spread[i] == 0); a dof on them (spread[i] != 0) takes a weighted mean
 * of the dofs off the surfaces that the mass matrix (triplets Mi, Mj, Mv
 * [nm], duplicates allowed) couples to it.  Rows sum to 1 (total mass and
 * linear momentum kept), T T = T, and M_red has no mass on the surface
 * dofs, which then follow the quasi-static balance of elastic and contact
 * forces: no contact chatter, and the trapezoidal rule keeps the energy in
 * persistent contact.  With the dofs' positions X[n*3] the weights also
 * reproduce the coordinates, all three or, with the dofs' components
 * comp[n] (0, 1, 2; -1: all three), the two other than the dof's own:
 * T v = v for a rigid motion, so the centre of mass and the inertia tensor
 * are kept.  Where a dof's neighbours do not span those coordinates, dofs
 * two or three steps away join; *inexact counts the rows where even those
 * do not (their weights are then the neighbours' mean by |M_ij|).  X NULL:
 * the weights are |M_ij| / sum_j |M_ij| over the neighbours.  A surface
 * dof coupled to no dof off the surfaces (a body one element thick) keeps
 * its row e_i: *kept counts them.  T goes to the triplets (Ti, Tj, Tv)
 * [cap], *nt of them (the count needed, with FFC_ERR_CAPACITY). */
int ffc_mass_spread(long n, long nm, const long Mi[], const long Mj[], const double Mv[], const double X[],
                    const long comp[], const double spread[], long cap, long Ti[], long Tj[], double Tv[], long *nt,
                    long *kept, long *inexact);

/* ------------------------------------------------- quadratic tetrahedra */
/* Numbers the nodes of P2 tetrahedra T[nt*4] (nv vertices) as FreeFEM
 * numbers scalar P2 degrees of freedom: element by element, the 4 vertices
 * then the edges (0,1), (0,2), (0,3), (1,2), (1,3), (2,3), each node at its
 * first appearance.  node[nt*10] receives the nodes of each element,
 * *nnodes their count.  (For [P2,P2,P2] the dof of node i, component c is
 * 3 i + c.) */
int ffc_p2_number(long nt, const long T[], long nv, long node[], long *nnodes);

/* Positions X2[nnodes*3] of the P2 nodes of straight-sided tetrahedra:
 * the vertices and the edge midpoints of X[nv*3]. */
int ffc_p2_positions(long nt, const long T[], const long node[], const double X[],
                     long nnodes, double X2[]);

/* The 6 nodes of the face (face[3], vertex numbers, in facet order) of the
 * tetrahedron T4 with nodes node10: the 3 vertex nodes, then the mid-edge
 * nodes of edges 0-1, 1-2, 2-0 of the face. */
int ffc_p2_face(const long T4[4], const long node10[10], const long face[3], long out[6]);

#ifdef __cplusplus
}
#endif
#endif /* FFC_API_BULK_H */
