/* ffc.h: public C interface of the ffcontact kernels (3D contact geometry,
 * contact search and contact links for FreeFEM), free of FreeFEM types:
 * the headers of include/ffc/, layer by layer. */
#ifndef FFC_H
#define FFC_H

#include "ffc/status.h"
#include "ffc/settings.h"
#include "ffc/geom.h"
#include "ffc/surface.h"
#include "ffc/search.h"
#include "ffc/mortar.h"
#include "ffc/obstacle.h"
#include "ffc/link.h"
#include "ffc/newton.h"
#include "ffc/scene.h"
#include "ffc/solve.h"
#include "ffc/nts.h"
#include "ffc/bulk.h"
#include "ffc/mpi.h"

#endif /* FFC_H */
