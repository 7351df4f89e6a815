// ffc_shim_driver.cpp: the calls of the scene driver's layers: the settings (ffcSet, ffcGet, ffcGetWord), the bulk law (ffcBulkIs, ffcBulkText), the Newton loops' line search (ffcLs*), the layers' reason constants.
#include "ffc_shim.hpp"

namespace ffc_shim {

namespace {

std::vector<basicAC_F0::name_and_type> set_names;   // the settings as named arguments (made at load)

std::string settings_list()
{
    std::string l;
    for (int i = 0; i < ffc_settings_count(); i++) l += std::string(i ? " " : "") + ffc_setting_at(i)->name;
    return l;
}

int need_setting(const char *fn, const std::string &name, bool word)
{
    const int i = ffc_setting_find(name.c_str());
    if (i < 0) fail(fn, "argument 'name': '" + name + "' is not a setting; the settings are: " + settings_list());
    if ((ffc_setting_at(i)->type == FFC_SET_WORD) != word)
        fail(fn, "argument 'name': '" + name + "' is " + (word ? "a number: ffcGet" : "a word: ffcGetWord"));
    return i;
}

} // namespace

basicAC_F0::name_and_type *settings_names(int *n)
{
    if (set_names.empty())
        for (int i = 0; i < ffc_settings_count(); i++) {
            const ffc_setting *t = ffc_setting_at(i);
            // (a whole-number setting takes a real too, so that 2.5 is refused, not cut to 2)
            set_names.push_back({t->name, t->type == FFC_SET_WORD ? &typeid(string *) : &typeid(double)});
        }
    *n = (int)set_names.size();
    return set_names.data();
}

// ffcSet(C, name = value, ...): the settings given, each checked; a refused
// one changes none of them
long sceneSet(const Named &nm, FFScene *const &C)
{
    const char *fn = "ffcSet";
    SceneData &d = need_scene(fn, C);
    ffc_settings next = *ffc_scene_settings(d.s);
    ffc_error err = {};
    for (int i = 0; i < ffc_settings_count(); i++) {
        if (!nm.has(i)) continue;
        const ffc_setting *t = ffc_setting_at(i);
        int st;
        if (t->type == FFC_SET_WORD) st = ffc_settings_set_word(&next, t->name, nm.str(i, "").c_str(), &err);
        else st = ffc_settings_set(&next, t->name, nm.real(i, 0.0), &err);
        if (st) fail(fn, std::string("argument ") + err.msg + " (" + t->what + ")");
    }
    *ffc_scene_settings(d.s) = next;
    return 0;
}

// ffcGet(C, name): a number setting
double sceneGet(const Named &, FFScene *const &C, string *const &name)
{
    const char *fn = "ffcGet";
    SceneData &d = need_scene(fn, C);
    const std::string n = name ? *name : "";
    need_setting(fn, n, false);
    double v = 0;
    ffc_settings_get(ffc_scene_settings(d.s), n.c_str(), &v);
    return v;
}

// ffcGetWord(C, name): a word setting
string *sceneGetWord(const Named &nm, FFScene *const &C, string *const &name)
{
    const char *fn = "ffcGetWord";
    SceneData &d = need_scene(fn, C);
    const std::string n = name ? *name : "";
    need_setting(fn, n, true);
    char w[64];
    ffc_settings_word(ffc_scene_settings(d.s), n.c_str(), w, sizeof w);
    return Add2StackOfPtr2Free(nm.s, new string(w));
}

// ffcBulkIs(C, what): 1 when the scene's bulk is what ("linear",
// "symmetric", "finite", its kind "elastic", "neohookean", "svk",
// "mooneyrivlin", "user", or "hyperelastic": one of the three laws in C)
long sceneBulkIs(const Named &, FFScene *const &C, string *const &what)
{
    const char *fn = "ffcBulkIs";
    SceneData &d = need_scene(fn, C);
    ffc_bulk_law l;
    ffc_scene_law(d.s, &l);
    const std::string w = what ? *what : "";
    if (w == "linear") return l.linear;
    if (w == "symmetric") return l.symmetric;
    if (w == "finite") return l.finite;
    if (w == "elastic") return l.kind == FFC_BULK_LINEAR;
    if (w == "neohookean") return l.kind == FFC_BULK_NEOHOOKEAN;
    if (w == "svk") return l.kind == FFC_BULK_SVK;
    if (w == "mooneyrivlin") return l.kind == FFC_BULK_MOONEYRIVLIN;
    if (w == "user") return l.kind == FFC_BULK_USER;
    if (w == "hyperelastic") return l.kind == FFC_BULK_NEOHOOKEAN || l.kind == FFC_BULK_SVK || l.kind == FFC_BULK_MOONEYRIVLIN;
    fail(fn, "argument 'what': '" + w + "' is not linear, symmetric, finite, elastic, neohookean, svk, mooneyrivlin, "
             "hyperelastic or user");
}

// ffcBulkText(C): the bulk in words ("neohookean: nonlinear, symmetric, finite deformation")
string *sceneBulkText(const Named &nm, FFScene *const &C)
{
    SceneData &d = need_scene("ffcBulkText", C);
    ffc_bulk_law l;
    ffc_scene_law(d.s, &l);
    std::string t = std::string("bulk = \"") + bulk_name(l.kind) + "\": " + (l.linear ? "linear" : "nonlinear") + ", " +
                    (l.symmetric ? "symmetric" : "not symmetric") + ", " + (l.finite ? "finite deformation" : "small strain");
    return Add2StackOfPtr2Free(nm.s, new string(t));
}

// The driver's line search (ffc_ls_*; its settings maxLineSearch and lsTol):
// ffcLsStart(C, a0, g0, rn, secant, guard); while (ffcLsNext(C)) { a = ffcLsPoint(C); ...
// ffcLsReport(C, g, |r|, fullTaken) or ffcLsReject(C) }; a = ffcLsPoint(C); ffcLsCuts(C)
long sceneLsStart(const Named &, FFScene *const &C, const double &a0, const double &g0, const double &rn,
                  const bool &secant, const bool &guard)
{
    const char *fn = "ffcLsStart";
    SceneData &d = need_scene(fn, C);
    double mls = 0, tol = 0;
    ffc_settings_get(ffc_scene_settings(d.s), "maxLineSearch", &mls);
    ffc_settings_get(ffc_scene_settings(d.s), "lsTol", &tol);
    if (!(a0 > 0 && a0 <= 1)) fail(fn, "argument 'a0': " + num(a0) + " is not in (0, 1]");
    ffc_ls_start(ffc_scene_line_search(d.s), (int)mls, tol, a0, g0, rn, secant, guard);
    return 0;
}

long sceneLsNext(const Named &, FFScene *const &C)
{
    SceneData &d = need_scene("ffcLsNext", C);
    double a = 0;
    return ffc_ls_next(ffc_scene_line_search(d.s), &a) == 1;
}

double sceneLsPoint(const Named &, FFScene *const &C)
{
    SceneData &d = need_scene("ffcLsPoint", C);
    return ffc_scene_line_search(d.s)->a;
}

long sceneLsReport(const Named &, FFScene *const &C, const double &g, const double &rnorm, const bool &full)
{
    const char *fn = "ffcLsReport";
    SceneData &d = need_scene(fn, C);
    if (ffc_ls_report(ffc_scene_line_search(d.s), g, rnorm, full)) fail(fn, "no point to report on (ffcLsNext first)");
    return 0;
}

long sceneLsReject(const Named &, FFScene *const &C)
{
    const char *fn = "ffcLsReject";
    SceneData &d = need_scene(fn, C);
    if (ffc_ls_reject(ffc_scene_line_search(d.s))) fail(fn, "no point to reject (ffcLsNext first)");
    return 0;
}

long sceneLsCuts(const Named &, FFScene *const &C)
{
    SceneData &d = need_scene("ffcLsCuts", C);
    return ffc_scene_line_search(d.s)->cuts;
}

// the layers' reasons as script constants: Newton (ffc_newton_reason), the
// augmentations and the load steps (ffc_step_reason); the columns of
// ffcPoints and ffcFreeMotions
void register_driver()
{
    typedef FFScene *S;
    int ns = 0;
    basicAC_F0::name_and_type *sn = settings_names(&ns);
    Global.Add("ffcSet", "(", named<long, S>("ffcSet", sn, ns, sceneSet));
    Global.Add("ffcGet", "(", named<double, S, string *>("ffcGet", nullptr, 0, sceneGet));
    Global.Add("ffcGetWord", "(", named<string *, S, string *>("ffcGetWord", nullptr, 0, sceneGetWord));
    Global.Add("ffcBulkIs", "(", named<long, S, string *>("ffcBulkIs", nullptr, 0, sceneBulkIs));
    Global.Add("ffcBulkText", "(", named<string *, S>("ffcBulkText", nullptr, 0, sceneBulkText));
    Global.Add("ffcLsStart", "(", named<long, S, double, double, double, bool, bool>("ffcLsStart", nullptr, 0, sceneLsStart));
    Global.Add("ffcLsNext", "(", named<long, S>("ffcLsNext", nullptr, 0, sceneLsNext));
    Global.Add("ffcLsPoint", "(", named<double, S>("ffcLsPoint", nullptr, 0, sceneLsPoint));
    Global.Add("ffcLsReport", "(", named<long, S, double, double, bool>("ffcLsReport", nullptr, 0, sceneLsReport));
    Global.Add("ffcLsReject", "(", named<long, S>("ffcLsReject", nullptr, 0, sceneLsReject));
    Global.Add("ffcLsCuts", "(", named<long, S>("ffcLsCuts", nullptr, 0, sceneLsCuts));
    const struct { const char *name; long v; } k[] = {
        {"ffcNewtonConverged", FFC_NEWTON_CONVERGED}, {"ffcNewtonMaxIt", FFC_NEWTON_MAXIT},
        {"ffcNewtonNoDescent", FFC_NEWTON_NODESCENT}, {"ffcNewtonLinear", FFC_NEWTON_LINEAR},
        {"ffcNewtonCapacity", FFC_NEWTON_CAPACITY},   {"ffcStepConverged", FFC_STEP_CONVERGED},
        {"ffcStepAugment", FFC_STEP_AUGMENT},         {"ffcStepNoPair", FFC_STEP_NOPAIR},
        {"ffcStepMaterial", FFC_STEP_MATERIAL},       {"ffcStepTime", FFC_STEP_TIME},
        {"ffcStepSettings", FFC_STEP_SETTINGS},       {"ffcStepNewton", FFC_STEP_NEWTON},
        {"ffcStepSelfPassed", FFC_STEP_SELF_PASSED},
        // the columns of ffcPoints and of ffcFreeMotions, by name
        {"ffcPtX", FFC_PT_X}, {"ffcPtY", FFC_PT_Y}, {"ffcPtZ", FFC_PT_Z}, {"ffcPtGap", FFC_PT_GAP},
        {"ffcPtP", FFC_PT_P}, {"ffcPtActive", FFC_PT_ACTIVE}, {"ffcPtArea", FFC_PT_AREA},
        {"ffcPtFacet", FFC_PT_FACET}, {"ffcPtTx", FFC_PT_TX}, {"ffcPtTy", FFC_PT_TY}, {"ffcPtTz", FFC_PT_TZ},
        {"ffcPtState", FFC_PT_STATE}, {"ffcPtDiss", FFC_PT_DISS}, {"ffcPtCols", FFC_POINT_COLS},
        {"ffcMoBody", FFC_MO_BODY}, {"ffcMoT", FFC_MO_T}, {"ffcMoW", FFC_MO_W}, {"ffcMoP", FFC_MO_P},
        {"ffcMoX", FFC_MO_X}, {"ffcMoAmount", FFC_MO_AMOUNT}, {"ffcMoTet", FFC_MO_TET},
        {"ffcMoCols", FFC_MOTION_COLS}};
    for (const auto &c : k) Global.New(c.name, CConstant<long>(c.v));
}

} // namespace ffc_shim
