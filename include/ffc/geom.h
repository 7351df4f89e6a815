/* ffc/geom.h: effects, facet shape functions and geometry, quadrature, closest-point projection. */
#ifndef FFC_API_GEOM_H
#define FFC_API_GEOM_H

#include "status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------- effects */
/* What a scene computes: kernels skip every term whose effect is off. */
typedef struct {
    int friction;      /* 1: Coulomb friction terms, 0: frictionless (none computed) */
    int dynamic;       /* 1: velocity form with time step, 0: quasi-static */
    int finite_def;    /* 1: geometry of the current configuration x = X + u in
                          area elements and tangents, 0: small strain */
} ffc_effects;

/* ---------------------------------------------------- facet shape functions */
/* Triangle facets in local coordinates (xi1, xi2), area coordinates
 * L1 = 1 - xi1 - xi2, L2 = xi1, L3 = xi2.  Node order: 3 vertices at
 * (0,0), (1,0), (0,1); for 6 nodes then the mid-edge nodes of edges
 * 0-1, 1-2, 2-0. */
#define FFC_MAXNODES 6                  /* nodes of the largest facet */
#define FFC_MAXDOF (3 * 2 * FFC_MAXNODES) /* slave + master facet dofs of one link (36) */

/* N[nn] shape values, dN[nn][2] first derivatives d N_a / d xi_b.
 * Returns FFC_OK or FFC_ERR_NODES. */
int ffc_shape(int nn, const double xi[2], double N[FFC_MAXNODES],
              double dN[FFC_MAXNODES][2]);

/* d2N[nn][3] second derivatives (d11, d12, d22); zero for 3 nodes. */
int ffc_shape_d2(int nn, const double xi[2], double d2N[FFC_MAXNODES][3]);

/* Geometry of a facet at one point, in the configuration whose nodal
 * positions are given. */
typedef struct {
    double x[3];        /* position (length) */
    double tau[2][3];   /* covariant tangents dx/dxi_a (length) */
    double n[3];        /* unit normal tau1 x tau2 / |tau1 x tau2| (1) */
    double m[2][2];     /* surface metric m_ab = tau_a . tau_b (length^2) */
    double minv[2][2];  /* inverse metric m^ab (1/length^2) */
    double j;           /* area element |tau1 x tau2| (length^2 per unit xi-area) */
} ffc_point;

/* Position, tangents, normal, metric and area element at xi of the facet
 * with nodal positions X[nn][3].  FFC_ERR_DEGENERATE if j is not positive
 * relative to the square of the facet size. */
int ffc_facet_point(int nn, const double X[][3], const double xi[2],
                    ffc_point *p);

/* ------------------------------------------------------------ quadrature */
/* Gauss rules on the reference triangle (area 1/2), exact for polynomials
 * of total degree <= degree, degree 1..6: 1, 3, 6, 6, 7, 12 points.
 * Returns the number of points needed for degree (or FFC_ERR_QUAD). */
int ffc_quad_size(int degree);

/* Fills xi[npts][2] and w[npts] (weights summing to 1/2). cap is the
 * capacity of both arrays in points.  Returns the number of points,
 * FFC_ERR_QUAD, or FFC_ERR_CAPACITY if cap < ffc_quad_size(degree). */
int ffc_quad(int degree, int cap, double xi[][2], double w[]);

/* ------------------------------------------------------------ projection */
/* Where the foot of a projection lies on the facet. */
enum {
    FFC_FOOT_INSIDE = 0,   /* interior (or on the boundary within round-off) */
    FFC_FOOT_EDGE0 = 1,    /* clamped onto edge 0-1 (xi2 = 0) */
    FFC_FOOT_EDGE1 = 2,    /* clamped onto edge 1-2 (xi1 + xi2 = 1) */
    FFC_FOOT_EDGE2 = 3,    /* clamped onto edge 2-0 (xi1 = 0) */
    FFC_FOOT_VERTEX0 = 4,  /* clamped onto vertex 0 */
    FFC_FOOT_VERTEX1 = 5,
    FFC_FOOT_VERTEX2 = 6
};

/* Closest-point projection of a point p onto a facet. */
typedef struct {
    double xi[2];       /* local coordinates of the foot, inside the facet (1) */
    double xi_free[2];  /* stationary point of |p - x(xi)| without the facet
                           bounds; equals xi when where == FFC_FOOT_INSIDE (1) */
    double x[3];        /* foot position x(xi) (length) */
    double n[3];        /* unit facet normal at the foot (1) */
    double gap;         /* signed normal gap n . (p - x): > 0 on the side the
                           normal points to, < 0 below (length) */
    double dist;        /* |p - x| (length) */
    int where;          /* FFC_FOOT_* */
    int iters;          /* Newton iterations used (0 for flat facets) */
} ffc_proj;

/* Projects p onto the facet X[nn][3].  Returns FFC_OK when the foot is
 * inside, FFC_INFO_EDGE or FFC_INFO_VERTEX when it was clamped onto the
 * boundary (out->where says which), or a negative error. */
int ffc_project(int nn, const double X[][3], const double p[3], ffc_proj *out);

/* Derivatives of an interior projection with respect to the nodal
 * positions (equivalently displacements) of a slave facet and the master
 * facet.  The slave point is p = sum_a Ns[a] x_a (ns slave nodes with
 * fixed shape values Ns); the master facet is Xm[nm][3] and pr its
 * projection.  Unknowns are ordered [slave node 0 (x,y,z), ..., slave node
 * ns-1, master node 0, ..., master node nm-1]; nd = 3 (ns + nm).
 * Outputs (rows of stride FFC_MAXDOF, first nd entries used):
 *   dxi[2][.]  d xi_a / d u,   dg[.]  d gap / d u,   dn[3][.]  d n_i / d u.
 * Valid for pr->where == FFC_FOOT_INSIDE; FFC_ERR_VALUE otherwise. */
int ffc_project_deriv(int ns, const double Ns[], int nm, const double Xm[][3],
                      const ffc_proj *pr, double dxi[2][FFC_MAXDOF],
                      double dg[FFC_MAXDOF], double dn[3][FFC_MAXDOF]);

#ifdef __cplusplus
}
#endif
#endif /* FFC_API_GEOM_H */
