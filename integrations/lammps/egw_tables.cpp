/* pair_style egw and fix wall/egw: the process-wide registry of hysteresis tables and the
 * ln-mu interpolation error estimate (egw_tables.h). */
#include "egw_tables.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <omp.h>
#include <system_error>
#include <thread>
#include <tuple>
#include <unistd.h>

using namespace LAMMPS_NS;
using namespace LAMMPS_NS::EgwTables;

bool HystKey::operator<(const HystKey &o) const
{
  return std::tie(model, mu, psi, K, rho, xmax, tol, flow_pressure, radius) <
      std::tie(o.model, o.mu, o.psi, o.K, o.rho, o.xmax, o.tol, o.flow_pressure, o.radius);
}

bool SliceKey::operator<(const SliceKey &o) const
{
  return std::tie(kind, model, mu, mu_lo, mu_hi, psi, K, rho, xmax, tol) <
      std::tie(o.kind, o.model, o.mu, o.mu_lo, o.mu_hi, o.psi, o.K, o.rho, o.xmax, o.tol);
}

SliceSet::~SliceSet()
{
  for (auto &t : tables) egw_table_free(&t);
}

namespace {

// the registry keeps a reference to every table it handed out, so that a law that is
// rebuilt (or another fix) finds it again; purge() lets go of those nobody else holds
std::mutex registry_mutex;
std::map<HystKey, Hyst> registry;
std::map<SliceKey, Slices> slice_registry;

Hyst own(egw_hysteresis h)
{
  return Hyst(h, [](egw_hysteresis p) { egw_hysteresis_free(&p); });
}

std::string last_error()
{
  char buf[1024];
  egw_last_error(buf, sizeof(buf));
  return buf;
}

// a fresh file name for one table in transit (egw's reader and writer take paths)
std::string temp_path()
{
  const char *dir = std::getenv("TMPDIR");
  std::string path = std::string(dir && *dir ? dir : "/tmp") + "/egw-lammps-XXXXXX";
  int fd = mkstemp(&path[0]);
  if (fd < 0) return std::string();
  close(fd);
  return path;
}

// status 0 and the file's bytes, or an egw status and its message
int serialize(egw_hysteresis h, std::string &bytes)
{
  std::string path = temp_path();
  if (path.empty()) {
    bytes = "cannot create a temporary file in $TMPDIR or /tmp to send a table to the other "
            "ranks";
    return EGW_IO_ERROR;
  }
  int st = egw_hysteresis_write(h, path.c_str(), EGW_FORMAT_BINARY);
  if (st) {
    bytes = last_error();
  } else {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  std::remove(path.c_str());
  return st;
}

int deserialize(const std::string &bytes, egw_hysteresis &h, std::string &message)
{
  std::string path = temp_path();
  if (path.empty()) {
    message = "cannot create a temporary file in $TMPDIR or /tmp to receive a table";
    return EGW_IO_ERROR;
  }
  {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), (std::streamsize) bytes.size());
  }
  int st = egw_hysteresis_read(path.c_str(), &h);
  if (st) message = last_error();
  std::remove(path.c_str());
  return st;
}

// force at overlap x after the turning point xt (a new contact loaded to xt first)
double force_after(egw_hysteresis h, double xt, double x)
{
  double s = -HUGE_VAL, p = 0.0, dp;
  egw_hysteresis_eval(h, xt, &s, &p, &dp);
  egw_hysteresis_eval(h, x, &s, &p, &dp);
  return p;
}

// Waits for every rank of comm without spinning: MPICH's blocking calls poll at full speed,
// and a rank waiting so for another's table build takes a core from that build's threads
// (2 ranks on 2 cores: the EP-GW set-up 1.28 s against 0.95 s on 1 rank)
void quiet_barrier(MPI_Comm comm)
{
  MPI_Request req;
  MPI_Ibarrier(comm, &req);
  int done = 0;
  MPI_Test(&req, &done, MPI_STATUS_IGNORE);
  while (!done) {
    usleep(200);
    MPI_Test(&req, &done, MPI_STATUS_IGNORE);
  }
}

// The ranks of comm that share this rank's node, and the processors a rank of the node
// may run on (the largest affinity mask among them: all the node's cores when the ranks
// are not bound, one when each is bound to its own)
void node_ranks(MPI_Comm comm, std::vector<int> &ranks, int &procs)
{
  MPI_Comm node;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int n = 1, me = 0, mine = std::max(1, omp_get_num_procs());
  MPI_Comm_size(node, &n);
  MPI_Comm_rank(comm, &me);
  ranks.assign(n, 0);
  MPI_Allgather(&me, 1, MPI_INT, ranks.data(), 1, MPI_INT, node);
  MPI_Allreduce(&mine, &procs, 1, MPI_INT, MPI_MAX, node);
  MPI_Comm_free(&node);
}

// the check points: (turning point, overlap) pairs in units of sigma
std::vector<std::pair<double, double>> check_points(double xc, double xmax)
{
  std::vector<std::pair<double, double>> pts;
  for (double xt : {2.0, 10.0, 0.2 * xmax, 0.5 * xmax})
    for (double f : {1.0, 0.95, 0.8, 0.5, 0.2, 0.0})
      if (xt <= xmax) pts.emplace_back(xt, xc + f * (xt - xc));
  return pts;
}

}    // namespace

EgwTables::BuildThreads::BuildThreads(int n_threads) : before(omp_get_max_threads())
{
  omp_set_num_threads(n_threads > 0 ? n_threads : std::max(1, omp_get_num_procs()));
}

EgwTables::BuildThreads::~BuildThreads()
{
  omp_set_num_threads(before);
}

std::vector<Hyst> EgwTables::hysteresis(const std::vector<HystKey> &keys, MPI_Comm comm,
                                        int n_threads,
                                        const std::function<void(const std::string &)> &fail,
                                        int *n_built)
{
  int me = 0, nprocs = 1;
  MPI_Comm_rank(comm, &me);
  MPI_Comm_size(comm, &nprocs);
  std::vector<Hyst> out(keys.size());
  std::vector<size_t> missing;
  {
    std::lock_guard<std::mutex> lock(registry_mutex);
    for (size_t i = 0; i < keys.size(); i++) {
      auto it = registry.find(keys[i]);
      if (it != registry.end()) out[i] = it->second;
      else if (std::find_if(missing.begin(), missing.end(), [&](size_t j) {
                 return !(keys[j] < keys[i]) && !(keys[i] < keys[j]);
               }) == missing.end())
        missing.push_back(i);
    }
  }
  std::vector<std::string> build_error(missing.size());
  // every rank holds the same tables (the same calls in the same order), so missing is
  // the same list everywhere; table m is built on rank m % nprocs, in rounds of nprocs
  // tables. With n_threads 0 the node's processors are shared among its ranks that build
  // in a round: 3 tables on 2 ranks of a 2-core node take one thread each for the first
  // two, then two threads for the third while the other rank waits (quiet_barrier)
  std::vector<int> local;
  int node_procs = 1;
  if (n_threads <= 0 && !missing.empty()) node_ranks(comm, local, node_procs);
  BuildThreads team(n_threads > 0 ? n_threads : 1);
  // table m of missing with threads threads (egw's OpenMP loops over its curves and
  // points take the default team, set here; o.n_threads its solver's)
  auto build_one = [&](size_t m, int threads) {
    const HystKey &k = keys[missing[m]];
    omp_set_num_threads(threads);
    egw_params p;
    egw_params_default(&p);
    p.model = k.model, p.radius = 1, p.modulus = 1, p.sigma = 1, p.mu = k.mu;
    p.psi = k.psi, p.hardness_coeff = k.K, p.plastic_ratio = k.rho;
    if (k.flow_pressure > 0 && k.radius > 0) {    // rough + cap: R/sigma, p_y/E*
      p.radius = k.radius, p.flow_pressure = k.flow_pressure;
    } else if (k.flow_pressure > 0) {    // Hertz + cap: only R, E*, p_y count (the rest default)
      egw_params_default(&p);
      p.model = EGW_MODEL_HERTZ, p.radius = 1, p.modulus = 1, p.sigma = 0;
      p.flow_pressure = k.flow_pressure;
    }
    egw_options o;
    egw_options_default(&o);
    o.n_threads = threads;
    egw_hysteresis h = nullptr;
    if (egw_hysteresis_build(&p, &o, 0.0, k.xmax, k.tol, &h)) build_error[m] = last_error();
    else out[missing[m]] = own(h);
  };
  // One rank with several processors and several tables to build: side by side, one
  // thread each (dynamic order), an odd one out first with every thread. A table's build
  // does not share its processors well (its OpenMP loops wait for their slowest curve
  // or point, and its loading table and curve phases follow one another); two tables
  // side by side keep both cores busy. The tables are the same whatever the threads (egw
  // builds them bit for bit alike on 1 or more threads).
  int procs = std::max(1, std::min(omp_get_num_procs(), node_procs));
  if (nprocs == 1 && n_threads <= 0 && procs >= 2 && missing.size() >= 2) {
    size_t n = missing.size(), lead = n > (size_t) procs ? n % (size_t) procs : 0;
    for (size_t m = 0; m < lead; m++) build_one(m, procs);
    // (threads of their own, each its own OpenMP team of one: the plugin is not compiled
    // with OpenMP pragmas)
    std::atomic<size_t> next(lead);
    auto worker = [&]() {
      for (size_t m = next++; m < n; m = next++) build_one(m, 1);
    };
    std::vector<std::thread> side;
    try {
      for (size_t w = 1; w < std::min((size_t) procs, n - lead); w++) side.emplace_back(worker);
    } catch (const std::system_error &) {    // no thread: this one builds what is left
    }
    worker();
    for (auto &t : side) t.join();
  } else {
    for (size_t m = 0; m < missing.size(); m++) {
      int owner = (int) (m % nprocs);
      if (owner != me) continue;
      int threads = n_threads;
      if (threads <= 0) {
        size_t round = m - m % nprocs;
        int builders = 0;
        for (int w : local)
          if (round + w < missing.size()) builders++;
        threads = std::max(1, std::min(omp_get_num_procs(), node_procs / std::max(1, builders)));
      }
      build_one(m, threads);
    }
  }
  // send each table (or its build's failure) from its owner to the others
  if (nprocs > 1 && !missing.empty()) quiet_barrier(comm);
  std::string first_error;
  for (size_t m = 0; m < missing.size(); m++) {
    int owner = (int) (m % nprocs);
    size_t i = missing[m];
    std::string bytes;
    int st = 0;
    if (owner == me) {
      if (!out[i]) {
        st = EGW_NOT_CONVERGED;
        bytes = build_error[m];
      } else if (nprocs > 1)
        st = serialize(out[i].get(), bytes);
    }
    if (nprocs > 1) {
      long n[2] = {(long) st, (long) bytes.size()};
      MPI_Bcast(n, 2, MPI_LONG, owner, comm);
      st = (int) n[0];
      bytes.resize((size_t) n[1]);
      if (n[1] > 0) MPI_Bcast(&bytes[0], (int) n[1], MPI_CHAR, owner, comm);
      if (owner != me && st == 0) {
        egw_hysteresis h = nullptr;
        std::string msg;
        st = deserialize(bytes, h, msg);
        if (st == 0) out[i] = own(h);
        else bytes = msg;
      }
      // a rank that could not read the table stops every rank
      int bad = st != 0, any = 0;
      MPI_Allreduce(&bad, &any, 1, MPI_INT, MPI_MAX, comm);
      if (any && !bad) st = EGW_IO_ERROR, bytes = "another rank could not read a table";
    }
    if (st && first_error.empty()) first_error = bytes;
  }
  if (!first_error.empty()) fail(first_error);
  {
    std::lock_guard<std::mutex> lock(registry_mutex);
    for (size_t m = 0; m < missing.size(); m++) registry[keys[missing[m]]] = out[missing[m]];
    for (size_t i = 0; i < keys.size(); i++)
      if (!out[i]) out[i] = registry[keys[i]];    // a key repeated in the list
  }
  if (n_built) *n_built = (int) missing.size();
  return out;
}

bool Inline::make(const std::vector<egw_table> &tables)
{
  *this = Inline();
  if (tables.empty()) return false;
  egw_table_info in;
  if (egw_table_get_info(tables[0], &in) != EGW_OK || in.n_nodes < 2) return false;
  int nn = in.n_nodes, k = 0;
  std::vector<double> xk(nn), ck(4 * (nn - 1));
  std::vector<double> coef(4 * (nn - 1) * tables.size());
  for (egw_table t : tables) {
    int nl = 0;
    if (egw_table_get_interpolant(t, nn, xk.data(), ck.data(), &nl) != EGW_OK) return false;
    if (k == 0) x = xk, n_log = nl;
    if (xk != x || nl != n_log) {    // another table's nodes: no shared lookup
      x.clear();
      return false;
    }
    for (int i = 0; i + 1 < nn; i++)
      for (int j = 0; j < 4; j++)
        coef[4 * (i * tables.size() + k) + j] = ck[4 * i + j];
    k++;
  }
  c.swap(coef);
  ns = (int) tables.size();
  x_lo = x.front(), x_hi = x.back();
  // buckets: about 8 per interval, doubled while one spans more than 8 intervals (nodes
  // crowd near the cut-off and contact; a scan of a few nodes is cheaper than a search).
  // A table reaching far (x_hi > 1024, sigma far below R) spaces its nodes geometrically
  // out there: buckets uniform in x would take 2^20 of them (4 MB, a cache miss a lookup)
  // and still scan, so they are uniform in bucket_coord, ~log2 x above 1
  log_buckets = x_hi > 1024.0;
  std::vector<double> u(nn);
  for (int i = 0; i < nn; i++) u[i] = log_buckets ? bucket_coord(x[i]) : x[i];
  origin = u.front();
  for (nb = 8 * (nn - 1);; nb *= 2) {
    scale = nb / (u.back() - origin);
    bucket.assign(nb, 0);
    int i = 0, widest = 0;
    for (int b = 0; b < nb; b++) {
      double xb = origin + (b - 1e-6) / scale;    // rounding never passes a bucket's start
      int i0 = i;
      while (i < nn - 2 && xb >= u[i + 1]) i++;
      bucket[b] = i;
      if (b > 0) widest = std::max(widest, i - i0);
    }
    if (widest <= 8 || nb >= (1 << 20)) break;
  }
  n = nn;
  take_tail(tables);
  return true;
}

bool Inline::take_tail(const std::vector<egw_table> &tables)
{
  n_piece = 0, tail_end = x_lo, piece_scale = 0.0;
  piece_x.clear(), piece_c.clear();
  int nt = (int) tables.size(), np = 0;
  // the size first, then the pieces (egw.h); a refusal leaves the exps
  if (egw_table_get_tail(nt, tables.data(), 0, nullptr, nullptr, &np) != EGW_OK || np < 1)
    return false;
  std::vector<double> xs(np + 1), pc(4 * (size_t) np * nt);
  if (egw_table_get_tail(nt, tables.data(), np, xs.data(), pc.data(), &np) != EGW_OK)
    return false;
  // egw_table_eval's piece of x: (x - starts[0]) * (N / (starts[N] - starts[0])), the same
  // doubles, so the same piece
  n_piece = np, tail_end = xs[np], piece_scale = np / (xs[np] - xs[0]);
  xs.pop_back();
  piece_x.swap(xs), piece_c.swap(pc);
  return true;
}

Slices EgwTables::find_slices(const SliceKey &key)
{
  std::lock_guard<std::mutex> lock(registry_mutex);
  auto it = slice_registry.find(key);
  return it == slice_registry.end() ? Slices() : it->second;
}

void EgwTables::keep_slices(const SliceKey &key, const Slices &set)
{
  std::lock_guard<std::mutex> lock(registry_mutex);
  slice_registry[key] = set;
}

void EgwTables::purge()
{
  std::lock_guard<std::mutex> lock(registry_mutex);
  for (auto it = registry.begin(); it != registry.end();)
    if (it->second.use_count() == 1) it = registry.erase(it);
    else ++it;
  for (auto it = slice_registry.begin(); it != slice_registry.end();)
    if (it->second.use_count() == 1) it = slice_registry.erase(it);
    else ++it;
}

int EgwTables::count()
{
  std::lock_guard<std::mutex> lock(registry_mutex);
  return (int) (registry.size() + slice_registry.size());
}

double EgwTables::lnmu_error_estimate(const std::vector<egw_hysteresis> &nodes, double xc,
                                      double xmax, std::vector<double> *per_interval)
{
  int n = (int) nodes.size();
  if (n < 3) return HUGE_VAL;
  // the second difference at every inner node, relative to its turning-point force
  std::vector<double> d2(n, 0.0);
  for (auto &pt : check_points(xc, xmax)) {
    for (int c = 1; c + 1 < n; c++) {
      double ft = force_after(nodes[c], pt.first, pt.first);
      if (!(ft > 0)) continue;
      double s = force_after(nodes[c - 1], pt.first, pt.second) -
          2.0 * force_after(nodes[c], pt.first, pt.second) +
          force_after(nodes[c + 1], pt.first, pt.second);
      d2[c] = std::max(d2[c], std::fabs(s) / ft);
    }
  }
  double err = 0.0;
  if (per_interval) per_interval->assign(n - 1, 0.0);
  for (int k = 0; k + 1 < n; k++) {
    double e = 0.125 * std::max(k >= 1 ? d2[k] : 0.0, k + 2 < n ? d2[k + 1] : 0.0);
    if (per_interval) (*per_interval)[k] = e;
    err = std::max(err, e);
  }
  return err;
}

double EgwTables::lnmu_error_midpoint(egw_hysteresis a, egw_hysteresis b, egw_hysteresis mid,
                                      double xc, double xmax)
{
  double err = 0.0;
  for (auto &pt : check_points(xc, xmax)) {
    double ft = force_after(mid, pt.first, pt.first);
    if (!(ft > 0)) continue;
    double pl = 0.5 * (force_after(a, pt.first, pt.second) + force_after(b, pt.first, pt.second));
    err = std::max(err, std::fabs(pl - force_after(mid, pt.first, pt.second)) / ft);
  }
  return err;
}
