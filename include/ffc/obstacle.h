/* ffc/obstacle.h: rigid obstacles given by their shape (plane, sphere, cylinder): gap, normal and curvature. */
#ifndef FFC_API_OBSTACLE_H
#define FFC_API_OBSTACLE_H

#include "status.h"
#include "geom.h"
#include "search.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A rigid master surface without a mesh and without degrees of freedom,
 * placed by the scene at each step.  Its signed distance phi(x) (> 0 on
 * the body's side, the open side) gives a slave point x its gap g =
 * phi(x), its unit normal n = grad phi (pointing into the body's side) and
 * the normal's derivative H = dn/dx (symmetric 3x3, 1/length):
 *   plane     phi = a . (x - c)                   H = 0
 *   sphere    phi = s (|d| - r),  d = x - c        H = s (I - n n) / |d|
 *   cylinder  phi = s (|d| - r),  d = (I - a a)(x - c)
 *                                                  H = s (I - a a - n n) / |d|
 * with n = s d / |d| and s = +1 for a body outside the shape (a ball or a
 * roller pressing on it), s = -1 for a body inside it (a spherical cup, a
 * bore).  The foot is x - g n; the gap's exact derivative is n, the
 * normal's H: the contact links' consistent tangent has the curvature
 * term without approximation. */
enum {
    FFC_OBST_PLANE = 1,
    FFC_OBST_SPHERE = 2,
    FFC_OBST_CYLINDER = 3
};

typedef struct {
    int kind;          /* FFC_OBST_* */
    double c[3];       /* plane: a point of it; sphere: the centre; cylinder: a point of the axis (length) */
    double a[3];       /* plane: the unit normal toward the body; cylinder: the unit axis; sphere: unused (1) */
    double r;          /* sphere, cylinder: radius (length), > 0; plane: unused */
    int inside;        /* sphere, cylinder: 1 the body is inside the shape, 0 outside; plane: 0 */
    double d[3];       /* the obstacle's motion, for friction against its surface: quasi-static, its
                          translation since the last converged step (length); dynamic, its velocity
                          (length/time) */
} ffc_obstacle;

/* FFC_OK, or FFC_ERR_VALUE (an unknown kind, a radius <= 0, a normal or
 * axis not of unit length to 1e-12, inside not 0 or 1, inside on a plane),
 * FFC_ERR_NONFINITE, FFC_ERR_NULL. */
int ffc_obstacle_check(const ffc_obstacle *ob);

/* An obstacle of kind (FFC_OBST_*) from a point c[3], a direction a[3]
 * (the plane's normal toward the body, the cylinder's axis; NULL for a
 * sphere) scaled here to unit length, radius r and inside: *ob, motion d
 * zero; ffc_obstacle_check's status, FFC_ERR_VALUE for a zero direction. */
int ffc_obstacle_make(int kind, const double c[3], const double a[3], double r, int inside, ffc_obstacle *ob);

/* The gap g, normal n[3] and H[3][3] = dn/dx at point x[3] (H may be
 * NULL).  FFC_ERR_DEGENERATE on a sphere's centre or a cylinder's axis
 * (no normal there). */
int ffc_obstacle_gap(const ffc_obstacle *ob, const double x[3], double *g, double n[3], double H[3][3]);

/* The facets of Fs[nf*nn] (node positions x[nv*3]) that face the
 * obstacle: their outward normal (vertices 0-2) opposes the obstacle's
 * normal at their centre (n_f . n < 0); facets on the centre or axis
 * count as not facing.  Returns the count, or an error.  A surface none of
 * whose facets faces the obstacle cannot touch it (a plane's normal given
 * pointing away from the body, a body meant to be inside given outside). */
long ffc_obstacle_facing(const ffc_obstacle *ob, int nn, long nf, const long F[], long nv, const double x[]);

/* Links of the slave surface Fs[nfs*nns] (node positions x[nv*3]) against
 * the obstacle, Gauss rule of degree qdeg: nfs * ffc_quad_size(qdeg)
 * links in the order (facet, point), as ffc_search: a point gets a link
 * (mf = 0, gap and normal filled, xm = 0) when its gap is at most
 * max(capture_abs, capture_rel h_f), h_f its slave facet's longest edge;
 * otherwise mf = -1.  Returns the number of linked points, or an error
 * (FFC_ERR_CAPACITY: cap < nfs * points per facet). */
int ffc_obstacle_search(const ffc_obstacle *ob, int nns, long nfs, const long Fs[], long nv, const double x[],
                        int qdeg, const ffc_search_opts *o, long cap, ffc_link links[]);

#ifdef __cplusplus
}
#endif
#endif /* FFC_API_OBSTACLE_H */
