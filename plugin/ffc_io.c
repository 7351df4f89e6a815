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
    static const char *names[3] = {"gap", "pressure", "active"};
    static const int cols[3] = {FFC_PT_GAP, FFC_PT_P, FFC_PT_ACTIVE};
    fprintf(f, "POINT_DATA %ld\n", n);
    for (int c = 0; c < 3; c++) {
        fprintf(f, "SCALARS %s double 1\nLOOKUP_TABLE default\n", names[c]);
        for (long k = 0; k < n; k++) {
            double v = P[k * FFC_POINT_COLS + cols[c]];
            fprintf(f, "%.17g\n", isfinite(v) ? v : -1.0); /* no partner: gap -1 */
        }
    }
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
