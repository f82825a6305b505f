/* C tests of the scene API (include/egw.h): default scene, reading namelist
 * files (good and bad), validation messages, the model choice and the build of its
 * tables through handles. Each egw_capi_test_scene_* returns the number of failed
 * checks and prints why; test/test_capi_scene.f90 runs them as a test-drive suite.
 * References: the Hertz closed form and the pair combination rules, written out here. */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include "egw.h"

static int failures;
static pthread_mutex_t failures_lock = PTHREAD_MUTEX_INITIALIZER;
#define CHECK(cond) do { if (!(cond)) { pthread_mutex_lock(&failures_lock); failures++; \
  pthread_mutex_unlock(&failures_lock); \
  printf("    C check failed at %s:%d: %s\n", __FILE__, __LINE__, #cond); } } while (0)

static double p_hertz(double e, double r, double d) {
  return d > 0.0 ? 4.0 / 3.0 * e * sqrt(r) * pow(d, 1.5) : 0.0;
}
static int last_error_names(const char *name) {
  char buf[512];
  if (egw_last_error(buf, (int)sizeof buf) < 1) return 0;
  return strstr(buf, name) != NULL;
}
static void write_text(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  if (f == NULL) return;
  fputs(text, f);
  fclose(f);
}

/* Default scene, validation messages, files. */
int egw_capi_test_scene_read(void) {
  egw_scene s, s0;
  const char *path = "scene_checks_tmp.nml";
  failures = 0;
  egw_scene_default(&s);
  egw_scene_default(NULL); /* ignored */
  CHECK(s.model == EGW_MODEL_EGW && s.n_types == 1 && s.radius[0] == 1e-3);
  CHECK(s.modulus[0] == 70e9 && s.poisson[0] == 0.22 && s.mu == 4.0);
  CHECK(s.sigma_min == 1e-6 && s.sigma_max == 1e-6 && s.delta_in_sigma == 1);
  CHECK(egw_scene_validate(&s) == EGW_OK);
  s0 = s;
  s.hardness_coeff = 1.5;
  CHECK(egw_scene_validate(&s) == EGW_INVALID_PARAMETER && last_error_names("hardness_coeff"));
  s = s0;
  s.n_types = 2; s.radius[1] = -1.0;
  CHECK(egw_scene_validate(&s) == EGW_INVALID_PARAMETER && last_error_names("radius(2)"));
  CHECK(egw_scene_validate(NULL) == EGW_NULL_POINTER);

  /* a good file changes what it gives */
  s = s0;
  write_text(path, "&scene\n radius = 1e-3, 2e-3\n sigma = 2e-7\n tol = 1e-3 /\n");
  CHECK(egw_scene_read(path, &s) == EGW_OK);
  CHECK(s.n_types == 2 && s.radius[1] == 2e-3 && s.sigma_max == 2e-7 && s.tol == 1e-3);
  CHECK(s.mu == 4.0 && s.modulus[0] == 70e9); /* kept from the default */
  /* bad files: named parameter, scene unchanged */
  s = s0;
  write_text(path, "&scene poisson = 0.9 /\n");
  CHECK(egw_scene_read(path, &s) == EGW_INVALID_PARAMETER && last_error_names("poisson(1)"));
  CHECK(memcmp(&s, &s0, sizeof s) == 0);
  write_text(path, "&scene radiuss = 1 /\n");
  CHECK(egw_scene_read(path, &s) == EGW_BAD_FILE && last_error_names("radiuss"));
  CHECK(memcmp(&s, &s0, sizeof s) == 0);
  remove(path);
  CHECK(egw_scene_read(path, &s) == EGW_IO_ERROR);
  CHECK(egw_scene_read(NULL, &s) == EGW_NULL_POINTER);
  CHECK(egw_scene_read(path, NULL) == EGW_NULL_POINTER);
  return failures;
}

/* Many threads read the same scene file at once (issue 22: with a Fortran open, ~40 of
 * 2400 calls failed "File already opened in another unit"): 8 threads x 300 reads of one
 * good file, each EGW_OK with the file's values (exact: the same decimal text parsed), and
 * every 10th a read of one bad file, refused with that thread's own message. */
enum { SCENE_THREADS = 8, SCENE_READS = 300 };
static const char *scene_good = "scene_checks_threads.nml";
static const char *scene_bad = "scene_checks_threads_bad.nml";
static void *scene_reader(void *arg) {
  (void)arg;
  for (int i = 0; i < SCENE_READS; i++) {
    egw_scene s;
    egw_scene_default(&s);
    CHECK(egw_scene_read(scene_good, &s) == EGW_OK);
    CHECK(s.n_types == 2 && s.radius[1] == 2e-3 && s.sigma_max == 2e-7 && s.tol == 1e-3);
    if (i % 10 == 0) {
      char own[512];
      CHECK(egw_scene_read(scene_bad, &s) == EGW_BAD_FILE);
      CHECK(egw_last_error(own, (int)sizeof own) <= (int)sizeof own &&
            strstr(own, "radiuss") != NULL);
    }
  }
  return NULL;
}
int egw_capi_test_scene_threads(void) {
  pthread_t threads[SCENE_THREADS];
  int started = 0;
  failures = 0;
  write_text(scene_good, "&scene\r\n radius = 1e-3, 2e-3 ! two types\n sigma = 2e-7\n"
                         " tol = 1e-3 /\n");
  write_text(scene_bad, "&scene radiuss = 1 /\n");
  for (int t = 0; t < SCENE_THREADS; t++)
    if (pthread_create(&threads[t], NULL, scene_reader, NULL) == 0) started++;
  CHECK(started == SCENE_THREADS);
  for (int t = 0; t < started; t++) pthread_join(threads[t], NULL);
  remove(scene_good);
  remove(scene_bad);
  return failures;
}

/* Hertz chosen for delta/sigma in [300, 3000] at tol 1e-2: the bound covers the
 * pointwise error at overlaps it did not sample (5 % margin: see test_scene.f90), and
 * egw_scene_build creates no handle. A smooth scene: Hertz exact, bound 0. */
int egw_capi_test_scene_hertz(void) {
  egw_scene s;
  egw_model_choice c;
  egw_options o;
  egw_params p;
  egw_result res;
  egw_table t = (egw_table)&s;       /* garbage on purpose: must come back NULL */
  egw_universal u = (egw_universal)&s;
  char reason[256];
  double r = 0.5e-3, e_star = 70e9 / (2.0 * (1.0 - 0.22 * 0.22)), worst = 0.0;
  failures = 0;
  egw_scene_default(&s);
  s.delta_min = 300.0; s.delta_max = 3000.0; s.tol = 1e-2;
  CHECK(egw_scene_choose(&s, NULL, &c, reason, (int)sizeof reason) == EGW_OK);
  CHECK(c.kind == EGW_CHOICE_HERTZ && c.hertz_relative_to_max == 0 && c.n_sets == 1);
  CHECK(c.error_bound > 0.0 && c.error_bound <= s.tol && c.n_solves > 0);
  CHECK(strstr(reason, "<= tol") != NULL);
  egw_params_default(&p);
  p.model = EGW_MODEL_EGW; p.radius = r; p.modulus = e_star; p.sigma = 1e-6; p.mu = 4.0;
  egw_options_default(&o);
  o.rel_tol = 1e-7;
  for (int i = 0; i < 10; i++) {
    double d = (300.0 + 2700.0 * (i + 0.5) / 10.0) * 1e-6;
    CHECK(egw_solve(&p, &o, d, &res) == EGW_OK);
    worst = fmax(worst, fabs(p_hertz(e_star, r, d) / res.force - 1.0));
  }
  CHECK(worst <= 1.05 * c.error_bound);
  CHECK(egw_scene_build(&s, NULL, &c, &t, &u) == EGW_OK);
  CHECK(c.kind == EGW_CHOICE_HERTZ && t == NULL && u == NULL);
  /* smooth spheres */
  s.sigma_min = s.sigma_max = 0.0; s.delta_in_sigma = 0; s.delta_min = 0.0; s.delta_max = 1e-5;
  CHECK(egw_scene_choose(&s, NULL, &c, NULL, 0) == EGW_OK);
  CHECK(c.kind == EGW_CHOICE_HERTZ && c.error_bound == 0.0 && c.n_solves == 0);
  CHECK(egw_scene_choose(&s, NULL, NULL, NULL, 0) == EGW_NULL_POINTER);
  return failures;
}

/* The default scene: a 1-D table whose force matches full solves within 1.5 tol (the
 * builder checks interval midpoints where the Hermite error peaks, 1.5 allows the
 * kernel to vary across an interval), with measured_error <= tol. */
int egw_capi_test_scene_table(void) {
  egw_scene s;
  egw_model_choice c;
  egw_params p;
  egw_options o;
  egw_result res;
  egw_table t = NULL;
  egw_universal u = NULL;
  double worst = 0.0, f, k;
  failures = 0;
  egw_scene_default(&s);
  CHECK(egw_scene_build(&s, NULL, &c, &t, &u) == EGW_OK);
  CHECK(c.kind == EGW_CHOICE_TABLE && t != NULL && u == NULL);
  CHECK(c.error_bound == s.tol && c.measured_error <= s.tol && c.n_nodes > 2);
  CHECK(c.hertz_error > s.tol && c.hertz_relative_to_max == 1);
  if (t == NULL) return failures;
  egw_params_default(&p);
  p.model = EGW_MODEL_EGW; p.radius = 0.5e-3; p.modulus = 70e9 / (2.0 * (1.0 - 0.22 * 0.22));
  p.sigma = 1e-6; p.mu = 4.0;
  egw_options_default(&o);
  o.rel_tol = 1e-7;
  for (int i = 0; i < 12; i++) {
    double d = (-2.0 + 22.0 * (i + 0.29) / 12.0) * 1e-6;
    CHECK(egw_solve(&p, &o, d, &res) == EGW_OK);
    CHECK(egw_table_eval(t, d, &f, &k) == EGW_OK);
    worst = fmax(worst, fabs(f / res.force - 1.0));
  }
  CHECK(worst <= 1.5 * s.tol);
  egw_table_free(&t);
  CHECK(t == NULL);
  /* invalid scene: no handle */
  s.tol = 0.5;
  t = NULL;
  CHECK(egw_scene_build(&s, NULL, &c, &t, &u) == EGW_INVALID_PARAMETER && t == NULL);
  CHECK(last_error_names("tol"));
  return failures;
}
