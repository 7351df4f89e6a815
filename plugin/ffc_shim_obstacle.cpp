// ffc_shim_obstacle.cpp: the FreeFEM calls of rigid obstacles (ffcAddObstacle, ffcMoveObstacle, ffcObstaclesAt).
#include "ffc_shim.hpp"

namespace ffc_shim {

basicAC_F0::name_and_type obstacle_names[OB_N];

void init_obstacle_names()
{
    for (int i = 0; i < PO_N; i++) obstacle_names[i] = pair_names[i];
    obstacle_names[OB_CENTER] = {"center", &typeid(E_Array)};
    obstacle_names[OB_RADIUS] = {"radius", &typeid(double)};
    obstacle_names[OB_AXIS] = {"axis", &typeid(E_Array)};
    obstacle_names[OB_NORMAL] = {"normal", &typeid(E_Array)};
    obstacle_names[OB_INSIDE] = {"inside", &typeid(long)};
    obstacle_names[OB_MOVE] = {"move", &typeid(E_Array)};
}

namespace {

const char *shape_name(int k) { return k == FFC_OBST_PLANE ? "plane" : k == FFC_OBST_SPHERE ? "sphere" : "cylinder"; }

// pair k's obstacle (argument k), or an error naming the pair
ffc_obstacle need_obstacle(const char *fn, const SceneData &d, long k, int *p)
{
    *p = need_pair_index(fn, d, k, false, "k");
    ffc_obstacle ob;
    if (ffc_scene_obstacle(d.s, *p, &ob)) {
        std::ostringstream s;
        s << "argument 'k': pair " << *p << " (" << d.labels[*p] << ") has no obstacle (ffcAddObstacle makes one)";
        fail(fn, s.str());
    }
    return ob;
}

// a 3-vector named argument i: from the script, or def (NULL: required)
void vec3(const char *fn, const Named &nm, int i, const double *def, double v[3], const char *why)
{
    if (!nm.vec3(i, v)) {
        if (!def) fail(fn, std::string("argument '") + nm.name(i) + "' is required: " + why);
        for (int k = 0; k < 3; k++) v[k] = def[k];
        return;
    }
    for (int k = 0; k < 3; k++) {
        if (!std::isfinite(v[k])) {
            std::ostringstream s;
            s << "argument '" << nm.name(i) << "': entry " << k << " is " << num(v[k]);
            fail(fn, s.str());
        }
    }
}

// The obstacle of the named arguments, kind given, from base (NULL: a new
// one, its required arguments required); *move its path (zero unless given).
ffc_obstacle named_obstacle(const char *fn, const Named &nm, int kind, const ffc_obstacle *base, double move[3])
{
    const double zero[3] = {0, 0, 0};
    double c[3], a[3] = {0, 0, 0};
    vec3(fn, nm, OB_CENTER, base ? base->c : nullptr, c,
         kind == FFC_OBST_PLANE ? "a point of the plane" : kind == FFC_OBST_SPHERE ? "the sphere's centre" : "a point of the cylinder's axis");
    vec3(fn, nm, OB_MOVE, zero, move, "");
    const int dir = kind == FFC_OBST_PLANE ? OB_NORMAL : OB_AXIS, other = kind == FFC_OBST_PLANE ? OB_AXIS : OB_NORMAL;
    if (kind != FFC_OBST_SPHERE)
        vec3(fn, nm, dir, base ? base->a : nullptr, a,
             kind == FFC_OBST_PLANE ? "the plane's normal, pointing toward the body" : "the cylinder's axis");
    auto refuse = [&](int i, const char *what) {
        if (nm.has(i)) fail(fn, std::string("argument '") + nm.name(i) + "': a " + shape_name(kind) + " has no " + what);
    };
    if (kind == FFC_OBST_SPHERE) refuse(OB_AXIS, "axis"), refuse(OB_NORMAL, "normal");
    else refuse(other, kind == FFC_OBST_PLANE ? "axis (its normal is 'normal')" : "normal (its direction is 'axis')");
    if (kind == FFC_OBST_PLANE) refuse(OB_RADIUS, "radius"), refuse(OB_INSIDE, "inside");
    const double r = nm.real(OB_RADIUS, base ? base->r : NAN);
    const long inside = nm.integer(OB_INSIDE, base ? base->inside : 0);
    if (kind != FFC_OBST_PLANE) {
        if (!nm.has(OB_RADIUS) && !base) fail(fn, "argument 'radius' is required: the " + std::string(shape_name(kind)) + "'s radius");
        if (!(r > 0) || std::isinf(r)) {
            std::ostringstream s;
            s << "argument 'radius': " << num(r) << " must be finite and > 0";
            fail(fn, s.str());
        }
        if (inside != 0 && inside != 1) {
            std::ostringstream s;
            s << "argument 'inside': " << inside << " is not 0 (the body outside the " << shape_name(kind) << ") or 1 (inside it)";
            fail(fn, s.str());
        }
    }
    ffc_obstacle ob;
    int st = ffc_obstacle_make(kind, c, a, r, (int)inside, &ob);
    if (st) {
        std::ostringstream s;
        s << "argument '" << nm.name(dir) << "': (" << num(a[0]) << ", " << num(a[1]) << ", " << num(a[2])
          << ") has no direction (zero length)";
        fail(fn, s.str());
    }
    return ob;
}

} // namespace

// ffcAddObstacle(C, slaveLabs, shape, center = [...], radius = r, axis = [...],
// normal = [...], inside = 0, move = [...], <pair options>): the surface
// slaveLabs against a rigid plane, sphere or cylinder; returns the pair's index.
long addObstacle(const Named &nm, FFScene *const &C, KN<long> *const &sl, string *const &shape)
{
    const char *fn = "ffcAddObstacle";
    SceneData &d = need_scene(fn, C);
    side_labels(fn, "slaveLabs", sl);
    const std::string sh = shape ? *shape : "";
    const int kind = sh == "plane" ? FFC_OBST_PLANE : sh == "sphere" ? FFC_OBST_SPHERE : sh == "cylinder" ? FFC_OBST_CYLINDER : 0;
    if (!kind) fail(fn, "argument 'shape': \"" + sh + "\" is not a shape of obstacles (\"plane\", \"sphere\", \"cylinder\")");
    double move[3];
    const ffc_obstacle ob = named_obstacle(fn, nm, kind, nullptr, move);
    ffc_pair_opts o = named_pair_opts(fn, nm, d, ffc_pair_defaults());
    if (o.method != FFC_METHOD_AL)
        fail(fn, std::string("argument 'method': an obstacle takes the augmented Lagrangian (\"al\")"));
    std::vector<long> Fs, tS;
    const long nfs = select_facets(fn, d, "slaveLabs", *sl, Fs, tS);
    // a surface none of whose facets faces the obstacle cannot touch it
    const double *X = d.order == 2 ? d.p2.X2.data() : d.m.X.data();
    if (ffc_obstacle_facing(&ob, d.order == 2 ? 6 : 3, nfs, Fs.data(), d.nn, X) == 0) {
        // (named by the arguments that place the shape against the surface:
        // any of them may be the one mistaken)
        std::ostringstream s;
        s << "no facet of the surface slaveLabs = " << labels_text(*sl) << " faces the " << shape_name(kind) << " (center = ("
          << num(ob.c[0]) << ", " << num(ob.c[1]) << ", " << num(ob.c[2]) << ")";
        if (kind == FFC_OBST_PLANE)
            s << ", normal = (" << num(ob.a[0]) << ", " << num(ob.a[1]) << ", " << num(ob.a[2])
              << "), which points toward the body, against the surface's outward normals): check the normal's sign and the label";
        else
            s << ", radius = " << num(ob.r) << ", inside = " << ob.inside << ": the body " << (ob.inside ? "inside" : "outside")
              << " it): check the label, the centre and inside";
        fail(fn, s.str());
    }
    long bad = -1;
    const int k = ffc_scene_add_obstacle(d.s, nfs, Fs.data(), &ob, &o, &bad);
    if (k < 0) scene_error(fn, k, bad, "the obstacle pair");
    int st = ffc_scene_set_obstacle(d.s, k, &ob, move);
    if (st) scene_error(fn, st, -1, "the obstacle's path");
    d.labels.push_back("slave " + labels_text(*sl) + " / rigid " + shape_name(kind));
    d.tetS.push_back(tS);
    d.tetM.push_back(std::vector<long>());
    return k;
}

long addObstacleL(const Named &nm, FFScene *const &C, long const &s, string *const &shape)
{
    KN<long> S(1);
    S[0] = s;
    return addObstacle(nm, C, &S, shape);
}

// ffcMoveObstacle(C, k, center = ..., move = ..., radius, axis, normal): pair k's
// obstacle placed anew at load factor 0 (what is not named stays) and its path
// (move: zero unless named); returns k.
long moveObstacle(const Named &nm, FFScene *const &C, long const &k)
{
    const char *fn = "ffcMoveObstacle";
    SceneData &d = need_scene(fn, C);
    int p;
    const ffc_obstacle base = need_obstacle(fn, d, k, &p);
    for (int i = 0; i < PO_N; i++)
        if (nm.has(i)) fail(fn, std::string("argument '") + nm.name(i) + "': a pair's options change with ffcSetPair");
    double move[3];
    const ffc_obstacle ob = named_obstacle(fn, nm, base.kind, &base, move);
    int st = ffc_scene_set_obstacle(d.s, p, &ob, move);
    if (st) scene_error(fn, st, -1, "the obstacle");
    return k;
}

// ffcObstaclesAt(C, lf): every obstacle at load factor lf (center + lf move).
long obstaclesAt(const Named &, FFScene *const &C, double const &lf)
{
    const char *fn = "ffcObstaclesAt";
    SceneData &d = need_scene(fn, C);
    if (!std::isfinite(lf)) {
        std::ostringstream s;
        s << "argument 'lf': " << num(lf) << " is not finite";
        fail(fn, s.str());
    }
    ffc_scene_obstacles_at(d.s, lf);
    return 0;
}

// ffcObstacle(C, k, what): pair k's obstacle now: "x", "y", "z" (centre or
// point), "radius", "nx", "ny", "nz" (normal or axis), "mx", "my", "mz"
// (its path's move).
double obstacleValue(const Named &, FFScene *const &C, long const &k, string *const &what)
{
    const char *fn = "ffcObstacle";
    SceneData &d = need_scene(fn, C);
    int p;
    const ffc_obstacle ob = need_obstacle(fn, d, k, &p);
    const std::string w = what ? *what : "";
    if (w == "x" || w == "y" || w == "z") return ob.c[w[0] - 'x'];
    if (w == "nx" || w == "ny" || w == "nz") return ob.a[w[1] - 'x'];
    if (w == "radius") return ob.r;
    if (w == "mx" || w == "my" || w == "mz") {
        double m[3];
        ffc_scene_obstacle_path(d.s, p, m);
        return m[w[1] - 'x'];
    }
    fail(fn, "argument 'what': \"" + w + "\" is not x, y, z, radius, nx, ny, nz, mx, my or mz");
}

} // namespace ffc_shim
