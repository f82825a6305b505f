/* pair_style egw: egw's rough-sphere normal contact (Hertz, GW, E-GW, EP-GW) as a LAMMPS
 * granular pair style, with coeff_restitution damping, Mindlin friction and per-contact
 * histories kept by a fix NEIGH_HISTORY.  Loaded as a plugin (egwplugin.cpp); see
 * integrations/lammps/README.md for the syntax and the physics.  The pair style composes
 * the normal law (egw_law.h), the sub-models (egw_submodels.h) and the contact histories
 * (egw_history.h). */
#ifndef EGW_PAIR_EGW_H
#define EGW_PAIR_EGW_H

#include "pair.h"

#include "egw.h"
#include "egw_law.h"
#include "egw_peers.h"

#include <cstdint>
#include <new>
#include <string>
#include <utility>
#include <vector>

namespace LAMMPS_NS {

class PairEGW : public Pair, public EgwTypeCoeffs {
 public:
  PairEGW(class LAMMPS *);
  ~PairEGW() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  double single(int, int, int, int, double, double, double, double &) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_restart_settings(FILE *) override;
  void read_restart_settings(FILE *) override;
  void transfer_history(double *, double *, int, int) override;
  double memory_usage() override;

 public:
  /* a type's own coefficients (pair_coeff I I); nullptr if not set (the wall fix reads them) */
  const EgwCoeff *type_coeff(int t) const override
  {
    return (allocated && t >= 1 && t < (int) pcoeff.size() && pcoeff[t][t].set) ? &pcoeff[t][t]
                                                                               : nullptr;
  }
  double type_radius_max(int t) const override
  {
    return t < (int) rad_max.size() ? rad_max[t] : 0.0;
  }
  double type_radius_min(int t) const override
  {
    return t < (int) rad_min.size() ? rad_min[t] : 0.0;
  }

 protected:
  int model;            // EGW_MODEL_*
  int nhist;            // doubles of history per contact (egw_history.h)
  int hist_sub;         // where the sub-models' history starts (-1: none)
  bool heat_any;        // some type pair has a heat model
  bool hyst_any;        // some type pair's law has hysteresis (EP-GW, the flow-pressure cap)
  double tol;           // table tolerance
  double rmin_user, rmax_user, overlap_max;
  double tail_energy;   // reference energy of the tail's reach (0: the tables' cut-off)
  class Fix *fix_history;
  bool list_was_size;              // the last run's list (for the log)
  double list_trigger;
  int freeze_group_bit;
  bool tables_ready;
  bool warned_range;
  int built_model;                           // settings the tables were built with
  double built_tol, built_overlap;    // one warning per rank for overlaps beyond the tables

  // per type (index 1..ntypes): own coefficients as given with pair_coeff I I
  using Coeff = EgwCoeff;
  std::vector<std::vector<Coeff>> pcoeff;    // [i][j], explicit pair_coeff I J
  std::vector<std::vector<EgwLaw>> law;      // [i][j] = [j][i]
  std::vector<double> rad_max, rad_min;      // per type, for cut-offs and table ranges
  std::vector<std::vector<double>> built_rlo, built_rhi;
  // compute()'s flat per-type-pair view [itype * (ntypes + 1) + jtype], both orders: the law
  // and its reach -delta_t (read for every neighbor, most of them beyond it)
  std::vector<EgwLaw *> law_of;
  std::vector<double> tail_of;

  void allocate();
  void parse_coeff(int, char **, Coeff &);
  void make_law(int, int, double R_lo, double R_hi);
  // type pairs whose rough + cap law was taken to its Hertz + cap limit: warned once
  std::vector<std::pair<int, int>> smooth_cap_warned;
  void check_law_model(const char *file);
  EgwSubmodels::Params mix_submodels(int, int, const EgwSubmodels::Params &,
                                     const EgwSubmodels::Params &);
  void build_tables(int, int, double, double);
  void type_radii();
  void request_list();
  std::string plain_reason(double tail_max, const std::string &box_fixes) const;
  void egw_fail(const std::string &what);
  inline void normal(EgwLaw &, double delta, double R, double *hist, double *cache, double &F,
                     double &S, double &U, int want_energy, EgwMemo *memo = nullptr);
  void report(const EgwLaw &, int st, double delta, double R);
  [[gnu::cold, gnu::noinline]] void not_finite(const EgwLaw &, int i, int j, double delta,
                                               double R, double F, double S);
  // per neighbor-list entry: entry jj of ilist[ii] is entry_first[ii] + jj (rebuilt with
  // the list, list_rows())
  std::vector<size_t> entry_first;
  bigint rows_calls = -1;
  void list_rows();
  // laws whose contacts keep an EgwMemo (1-D tables: the interval; nodes in ln mu or ln
  // R: their position there, a log once per contact and list instead of every step), one
  // per entry
  bool memo_any = false;
  std::vector<EgwMemo> entry_memo;
  // EP-GW: two hysteresis states per contact (blocks of HYST_CACHE doubles, which stay
  // where they are while their contact lasts), entry e uses block hyst_slot[e] (-1: none
  // yet); the slots are rebuilt with the list, the blocks of contacts no longer listed
  // reused (hyst_free) (egw_history.h)
  // Blocks of hyst_stride doubles: one state (EGW_HYSTERESIS_STATE_SIZE) when every law
  // has one table, two (HYST_CACHE) when one interpolates two (HYST_MU, rough + cap over
  // radii); on 64-byte lines, so that a state is 3 of them. compute() prefetches the block
  // of the entry HYST_PREFETCH ahead: a block is read from where its contact began, not in
  // list order, and waiting for it was half of the drum's EP-GW evaluations. Most entries
  // are pairs out of reach (a few instructions each): 2 entries ahead the block was still
  // on its way (the pair's share of the drum's perf samples, EP-GW: 2 ahead 16.7-17.8 %,
  // 4 ahead 14.6-16.1 %, 8 ahead 13.7-14.7 %, 16 ahead 14.5-14.9 %; doc/benchmarks.md
  // "Stop 50 (drum16)")
  static constexpr int HYST_PREFETCH = 8;
  template <class T> struct LineAllocator {
    using value_type = T;
    LineAllocator() = default;
    template <class U> LineAllocator(const LineAllocator<U> &) {}
    T *allocate(size_t n) { return (T *) ::operator new(n * sizeof(T), std::align_val_t(64)); }
    void deallocate(T *p, size_t) { ::operator delete(p, std::align_val_t(64)); }
    bool operator==(const LineAllocator &) const { return true; }
    bool operator!=(const LineAllocator &) const { return false; }
  };
  std::vector<double, LineAllocator<double>> hyst_cache;
  int hyst_stride = EgwHistory::HYST_CACHE;
  std::vector<int> hyst_slot;
  std::vector<tagint> hyst_cache_tags;     // the two atoms' IDs of each block
  std::vector<char> hyst_live;             // the block belongs to an entry of the list
  std::vector<int> hyst_free;              // blocks free for new contacts
  // the blocks by their pair's key (open addressing, key 0 empty), kept between rebuilds
  // so that a rebuild allocates nothing
  std::vector<std::pair<uint64_t, size_t>> hyst_old;
  double *hyst_block(size_t entry, tagint ti, tagint tj);
  void hyst_cache_rows();
};

}    // namespace LAMMPS_NS

#endif
