/* ffc_io.c: file output: contact points as a legacy-VTK point cloud and
 * masked columns of numbers as text. */
#include "ffc.h"

#include <math.h>
#include <stdio.h>

int ffc_points_vtk(const char *path, long n, const double P[])
{
    if (!path || (n > 0 && !P)) return FFC_ERR_NULL;
    if (n < 0) return FFC_ERR_SIZE;
    FILE *f = fopen(path, "w");
    if (!f) return FFC_ERR_VALUE;
    fprintf(f, "# vtk DataFile Version 3.0\ncontact points\nASCII\nDATASET POLYDATA\n");
    fprintf(f, "POINTS %ld double\n", n);
    for (long k = 0; k < n; k++)
        fprintf(f, "%.17g %.17g %.17g\n", P[k * FFC_POINT_COLS + FFC_PT_X], P[k * FFC_POINT_COLS + FFC_PT_Y],
                P[k * FFC_POINT_COLS + FFC_PT_Z]);
    fprintf(f, "VERTICES %ld %ld\n", n, 2 * n);
    for (long k = 0; k < n; k++) fprintf(f, "1 %ld\n", k);
    /* the point data: gap, pressure, contact status (0 open, 1 stick, 2
     * slip; a frictionless point in contact is 2), the friction traction
     * on the slave, the dissipation density */
    static const char *names[4] = {"gap", "pressure", "status", "dissipation"};
    fprintf(f, "POINT_DATA %ld\n", n);
    for (int c = 0; c < 4; c++) {
        fprintf(f, "SCALARS %s double 1\nLOOKUP_TABLE default\n", names[c]);
        for (long k = 0; k < n; k++) {
            const double *row = P + k * FFC_POINT_COLS;
            double v = c == 0 ? row[FFC_PT_GAP] : c == 1 ? row[FFC_PT_P] : c == 3 ? row[FFC_PT_DISS]
                     : row[FFC_PT_ACTIVE] == 0 ? 0.0 : row[FFC_PT_STATE] == 1 ? 1.0 : 2.0;
            fprintf(f, "%.17g\n", isfinite(v) ? v : -1.0); /* no partner: gap -1 */
        }
    }
    fprintf(f, "VECTORS friction_traction double\n");
    for (long k = 0; k < n; k++)
        fprintf(f, "%.17g %.17g %.17g\n", P[k * FFC_POINT_COLS + FFC_PT_TX], P[k * FFC_POINT_COLS + FFC_PT_TY],
                P[k * FFC_POINT_COLS + FFC_PT_TZ]);
    int bad = ferror(f);
    if (fclose(f) != 0 || bad) return FFC_ERR_VALUE;
    return FFC_OK;
}

int ffc_write_columns(const char *path, const char *header, long n, int ncol,
                      const double A[], const double mask[])
{
    if (!path || (n > 0 && !A)) return FFC_ERR_NULL;
    if (n < 0 || ncol < 1) return FFC_ERR_SIZE;
    FILE *f = fopen(path, "w");
    if (!f) return FFC_ERR_VALUE;
    if (header) fprintf(f, "# %s\n", header);
    for (long k = 0; k < n; k++) {
        if (mask && mask[k] == 0.0) continue;
        for (int j = 0; j < ncol; j++) fprintf(f, j ? " %.10g" : "%.10g", A[(long)j * n + k]);
        fputc('\n', f);
    }
    int bad = ferror(f);
    if (fclose(f) != 0 || bad) return FFC_ERR_VALUE;
    return FFC_OK;
}
