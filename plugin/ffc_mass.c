/* ffc_mass.c: mass redistribution for contact dynamics: the interpolation
 * T that gives the dofs of the contact surfaces the mean of their
 * neighbours off the surfaces, so that M_red = T' M T carries no mass on
 * them. */
#include <math.h>

#include "ffc.h"

/* Formulation: the kinetic energy of the redistributed mass is that of the
 * interpolated velocity, 1/2 (T v)' M (T v).  Row i of T is e_i off the
 * surfaces; on them, w_ij / sum_j w_ij over the dofs j off the surfaces that
 * M couples to i, w_ij = |M_ij| (the consistent P2 mass has negative
 * entries).  Each row sums to 1: a rigid translation is kept exactly, so
 * M_red has the total mass and the linear momentum of M; T is idempotent
 * (T T = T) and M_red's rows and columns of the surface dofs are zero. */
int ffc_mass_spread(long n, long nm, const long Mi[], const long Mj[], const double Mv[],
                    const double spread[], long cap, long Ti[], long Tj[], double Tv[], long *nt,
                    long *kept, double wsum[])
{
    if (!spread || !nt || !kept || !wsum || (nm > 0 && (!Mi || !Mj || !Mv)) || (cap > 0 && (!Ti || !Tj || !Tv)))
        return FFC_ERR_NULL;
    if (n <= 0 || nm < 0 || cap < 0) return FFC_ERR_SIZE;
    for (long k = 0; k < nm; k++) {
        if (Mi[k] < 0 || Mi[k] >= n || Mj[k] < 0 || Mj[k] >= n) return FFC_ERR_INDEX;
        if (!isfinite(Mv[k])) return FFC_ERR_NONFINITE;
    }
    for (long i = 0; i < n; i++) {
        if (!isfinite(spread[i])) return FFC_ERR_NONFINITE;
        wsum[i] = 0;
    }
    for (long k = 0; k < nm; k++)
        if (spread[Mi[k]] != 0 && spread[Mj[k]] == 0) wsum[Mi[k]] += fabs(Mv[k]);
    long need = 0, keep = 0;
    for (long i = 0; i < n; i++)
        if (spread[i] == 0 || !(wsum[i] > 0)) {
            need++;
            keep += spread[i] != 0;
        }
    for (long k = 0; k < nm; k++)
        if (spread[Mi[k]] != 0 && spread[Mj[k]] == 0 && wsum[Mi[k]] > 0 && Mv[k] != 0) need++;
    *nt = need;
    *kept = keep;
    if (need > cap) return FFC_ERR_CAPACITY;
    long t = 0;
    for (long i = 0; i < n; i++)
        if (spread[i] == 0 || !(wsum[i] > 0)) {
            Ti[t] = i;
            Tj[t] = i;
            Tv[t++] = 1.0;
        }
    for (long k = 0; k < nm; k++)
        if (spread[Mi[k]] != 0 && spread[Mj[k]] == 0 && wsum[Mi[k]] > 0 && Mv[k] != 0) {
            Ti[t] = Mi[k];
            Tj[t] = Mj[k];
            Tv[t++] = fabs(Mv[k]) / wsum[Mi[k]];
        }
    return FFC_OK;
}
