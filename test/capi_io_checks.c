/* C tests of egw's file output and input through include/egw.h (issue 13): many threads
 * writing and rereading tables at once, failed writes (a directory in the way, a missing
 * directory, a file-size limit) that must return EGW_IO_ERROR, keep the old file and
 * leave no temporary file, and paths longer than PATH_MAX. Each egw_capi_test_io_*
 * returns the number of failed checks and prints why; test/test_capi_io.f90 runs them. */
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>
#include "egw.h"

static int failures;
static pthread_mutex_t failures_lock = PTHREAD_MUTEX_INITIALIZER;
#define CHECK(cond) do { if (!(cond)) { pthread_mutex_lock(&failures_lock); failures++; \
  pthread_mutex_unlock(&failures_lock); \
  printf("    C check failed at %s:%d: %s\n", __FILE__, __LINE__, #cond); } } while (0)

static char message[20000];
static const char *last_message(void) {
  message[0] = '\0';
  egw_last_error(message, (int)sizeof message);
  return message;
}
/* Number of entries of dir whose name contains ".egw-tmp". */
static int temporaries_in(const char *dir) {
  DIR *d = opendir(dir);
  struct dirent *e;
  int n = 0;
  if (d == NULL) return -1;
  while ((e = readdir(d)) != NULL) n += strstr(e->d_name, ".egw-tmp") != NULL;
  closedir(d);
  return n;
}
/* The whole file (malloc'ed, NUL-terminated; *size bytes), NULL if unreadable. */
static char *slurp(const char *path, long *size) {
  FILE *fp = fopen(path, "rb");
  char *buf;
  if (fp == NULL) return NULL;
  fseek(fp, 0, SEEK_END);
  *size = ftell(fp);
  fseek(fp, 0, SEEK_SET);
  buf = malloc((size_t)*size + 1);
  if (buf != NULL && fread(buf, 1, (size_t)*size, fp) != (size_t)*size) {
    free(buf);
    buf = NULL;
  }
  if (buf != NULL) buf[*size] = '\0';
  fclose(fp);
  return buf;
}
static int same_file(const char *path, const char *content, long size) {
  long n = -1;
  char *now = slurp(path, &n);
  int same = now != NULL && n == size && memcmp(now, content, (size_t)size) == 0;
  free(now);
  return same;
}
static egw_table hertz_table(void) {
  egw_params p;
  egw_table t = NULL;
  egw_params_default(&p);
  p.model = EGW_MODEL_HERTZ; p.radius = 0.5; p.modulus = 2.0;
  if (egw_table_build(&p, NULL, 0.0, 0.01, 1e-6, &t) != EGW_OK) return NULL;
  return t;
}

/* ---------------------------------------------------------------- threads */

enum { n_threads = 16, n_rounds = 30 };
static egw_table shared_table;
static const char *thread_dir = "build/io_threads";

/* Each thread writes its own files (CSV and binary in turn, four names in rotation),
 * rereads each and compares it with the shared source table: same node count and
 * bit-identical forces at 7 overlaps (17 significant digits and the binary format
 * both reproduce every double). Between writes, a failing read of a path of its own
 * must leave that thread's own message in egw_last_error. */
static void *thread_work(void *arg) {
  int id = (int)(long)arg;
  char path[256], missing[256];
  egw_table_info a, b;
  egw_table_get_info(shared_table, &a);
  for (int i = 0; i < n_rounds; i++) {
    int format = i % 2 ? EGW_FORMAT_BINARY : EGW_FORMAT_CSV;
    egw_table r = NULL;
    snprintf(path, sizeof path, "%s/t%02d_%d.%s", thread_dir, id, i % 4, i % 2 ? "bin" : "csv");
    CHECK(egw_table_write(shared_table, path, format) == EGW_OK);
    CHECK(egw_table_read(path, &r) == EGW_OK && r != NULL);
    if (r == NULL) continue;
    CHECK(egw_table_get_info(r, &b) == EGW_OK && b.n_nodes == a.n_nodes);
    for (int j = 0; j < 7; j++) {
      double d = a.delta_max * (j + 0.37) / 7.0, f1 = -1, k1 = -1, f2 = -2, k2 = -2;
      egw_table_eval(shared_table, d, &f1, &k1);
      egw_table_eval(r, d, &f2, &k2);
      CHECK(f1 == f2 && k1 == k2);
    }
    egw_table_free(&r);
    snprintf(missing, sizeof missing, "%s/missing_%02d_%d.csv", thread_dir, id, i);
    CHECK(egw_table_read(missing, &r) == EGW_IO_ERROR && r == NULL);
    {
      char own[512], expect[300];
      egw_last_error(own, (int)sizeof own);
      snprintf(expect, sizeof expect, "path = %s: cannot open", missing);
      CHECK(strncmp(own, expect, strlen(expect)) == 0);
    }
  }
  return NULL;
}

int egw_capi_test_io_threads(void) {
  pthread_t threads[n_threads];
  failures = 0;
  mkdir("build", 0777);
  mkdir(thread_dir, 0777);
  shared_table = hertz_table();
  CHECK(shared_table != NULL);
  if (shared_table == NULL) return failures;
  for (long i = 0; i < n_threads; i++)
    CHECK(pthread_create(&threads[i], NULL, thread_work, (void *)i) == 0);
  for (int i = 0; i < n_threads; i++) pthread_join(threads[i], NULL);
  CHECK(temporaries_in(thread_dir) == 0);
  egw_table_free(&shared_table);
  return failures;
}

/* ---------------------------------------------------------------- failed writes */

static const char *fail_dir = "build/io_failures";

/* A write that cannot succeed: EGW_IO_ERROR naming the path, no temporary file left. */
static void refused_write(egw_table t, const char *path, int format, const char *reason) {
  char expect[600];
  CHECK(egw_table_write(t, path, format) == EGW_IO_ERROR);
  snprintf(expect, sizeof expect, "path = %s: ", path);
  CHECK(strncmp(last_message(), expect, strlen(expect)) == 0);
  if (strstr(message, reason) == NULL) {
    printf("    message lacks '%s': %s\n", reason, message);
    CHECK(0);
  }
}

int egw_capi_test_io_failures(void) {
  egw_table t;
  char path[512], *good;
  long good_size = 0;
  struct rlimit saved, small;
  const int formats[4] = {EGW_FORMAT_CSV, EGW_FORMAT_BINARY, EGW_FORMAT_LAMMPS,
                          EGW_FORMAT_CALCULIX};
  failures = 0;
  mkdir("build", 0777);
  mkdir(fail_dir, 0777);
  t = hertz_table();
  CHECK(t != NULL);
  if (t == NULL) return failures;
  /* a directory where the file should go: the rename fails, the temporary is removed */
  snprintf(path, sizeof path, "%s/a_directory", fail_dir);
  mkdir(path, 0777);
  snprintf(path, sizeof path, "%s/a_directory/inside", fail_dir);
  mkdir(path, 0777);
  snprintf(path, sizeof path, "%s/a_directory", fail_dir);
  for (int i = 0; i < 4; i++) refused_write(t, path, formats[i], "cannot rename");
  CHECK(temporaries_in(fail_dir) == 0);
  /* a missing directory: no temporary file can be created */
  snprintf(path, sizeof path, "%s/no_such_dir/t.csv", fail_dir);
  refused_write(t, path, EGW_FORMAT_CSV, "No such file or directory");
  /* a file-size limit (ulimit -f) below the file's size: refused before writing (a
   * write beyond it would raise SIGXFSZ and kill the process, leaving the temporary
   * file); the existing good file is unchanged, for each of the four formats */
  CHECK(getrlimit(RLIMIT_FSIZE, &saved) == 0);
  for (int i = 0; i < 4; i++) {
    snprintf(path, sizeof path, "%s/limited.%d", fail_dir, i);
    CHECK(egw_table_write(t, path, formats[i]) == EGW_OK);
    good = slurp(path, &good_size);
    CHECK(good != NULL && good_size > 256);
    small = saved;
    small.rlim_cur = 256;
    if (saved.rlim_max != RLIM_INFINITY && saved.rlim_max < small.rlim_cur)
      small.rlim_cur = saved.rlim_max;
    {
      void (*old_handler)(int) = signal(SIGXFSZ, SIG_IGN);
      CHECK(setrlimit(RLIMIT_FSIZE, &small) == 0);
      refused_write(t, path, formats[i], "ulimit -f");
      CHECK(setrlimit(RLIMIT_FSIZE, &saved) == 0);
      signal(SIGXFSZ, old_handler);
    }
    CHECK(good != NULL && same_file(path, good, good_size));
    free(good);
  }
  CHECK(temporaries_in(fail_dir) == 0);
  /* and the universal writer */
  {
    egw_params p;
    egw_universal u = NULL;
    egw_params_default(&p);
    p.model = EGW_MODEL_HERTZ; p.radius = 0.5; p.modulus = 2.0;
    if (egw_universal_build(&p, NULL, 0.5, 4.0, -1.0, 100.0, 1e-4, &u) == EGW_OK) {
      snprintf(path, sizeof path, "%s/universal.egwu", fail_dir);
      CHECK(egw_universal_write(u, path, EGW_FORMAT_BINARY) == EGW_OK);
      good = slurp(path, &good_size);
      small = saved;
      small.rlim_cur = 256;
      CHECK(setrlimit(RLIMIT_FSIZE, &small) == 0);
      CHECK(egw_universal_write(u, path, EGW_FORMAT_CSV) == EGW_IO_ERROR);
      CHECK(setrlimit(RLIMIT_FSIZE, &saved) == 0);
      CHECK(good != NULL && same_file(path, good, good_size));
      free(good);
      egw_universal_free(&u);
    } else {
      printf("    universal build failed: %s\n", last_message());
      CHECK(0);
    }
  }
  CHECK(temporaries_in(fail_dir) == 0);
  egw_table_free(&t);
  return failures;
}

/* ---------------------------------------------------------------- full disk */

/* The scenario itself, where it can be staged: as root, a 1 MiB tmpfs is
 * mounted, a good file of each of the four formats written to it, the rest of it filled
 * up; then every rewrite must return EGW_IO_ERROR ("No space left on device"), keep the
 * good file byte for byte and leave no temporary file. Not root, or no mount(8): the
 * check is skipped (the failures test covers the same code with a file-size limit, and
 * the text_io suite writes to /dev/full). */
int egw_capi_test_io_full_disk(void) {
  const char *mnt = "build/io_full_disk";
  const int formats[4] = {EGW_FORMAT_CSV, EGW_FORMAT_BINARY, EGW_FORMAT_LAMMPS,
                          EGW_FORMAT_CALCULIX};
  char path[4][256], cmd[512];
  char *good[4];
  long size[4];
  egw_table t;
  failures = 0;
  if (geteuid() != 0) {
    printf("    (not root: the full tmpfs check is skipped)\n");
    return 0;
  }
  mkdir("build", 0777);
  mkdir(mnt, 0777);
  snprintf(cmd, sizeof cmd, "mount -t tmpfs -o size=1m tmpfs %s 2>/dev/null", mnt);
  if (system(cmd) != 0) {
    printf("    (no tmpfs mount possible: the full tmpfs check is skipped)\n");
    return 0;
  }
  t = hertz_table();
  CHECK(t != NULL);
  for (int i = 0; i < 4 && t != NULL; i++) {
    snprintf(path[i], sizeof path[i], "%s/table.%d", mnt, i);
    CHECK(egw_table_write(t, path[i], formats[i]) == EGW_OK);
    good[i] = slurp(path[i], &size[i]);
    CHECK(good[i] != NULL);
  }
  {
    char filler[256], block[4096];
    FILE *fp;
    memset(block, 0, sizeof block);
    snprintf(filler, sizeof filler, "%s/filler", mnt);
    fp = fopen(filler, "wb");
    if (fp != NULL) {
      while (fwrite(block, 1, sizeof block, fp) == sizeof block && fflush(fp) == 0) {}
      fclose(fp);
    }
  }
  for (int i = 0; i < 4 && t != NULL; i++) {
    refused_write(t, path[i], formats[i], "No space left on device");
    CHECK(good[i] != NULL && same_file(path[i], good[i], size[i]));
    free(good[i]);
  }
  CHECK(temporaries_in(mnt) == 0);
  egw_table_free(&t);
  snprintf(cmd, sizeof cmd, "umount %s", mnt);
  CHECK(system(cmd) == 0);
  return failures;
}

/* ---------------------------------------------------------------- long paths */

/* Paths are read from C at their full length (strlen), never cut: a path of 3900
 * bytes (nested directories) works; one of 5000 bytes (beyond Linux's PATH_MAX of
 * 4096) is refused with EGW_IO_ERROR and a message that names the whole path (its
 * last characters included), by the table writer and reader, the scene reader and the
 * hysteresis reader. */
int egw_capi_test_io_long_paths(void) {
  egw_table t, r = NULL;
  static char path[6000];
  char component[201];
  size_t n;
  failures = 0;
  t = hertz_table();
  CHECK(t != NULL);
  if (t == NULL) return failures;
  mkdir("build", 0777);
  memset(component, 'd', 200);
  component[200] = '\0';
  strcpy(path, "build/io_long");
  mkdir(path, 0777);
  while (strlen(path) < 3600) {
    strcat(path, "/");
    strcat(path, component);
    mkdir(path, 0777);
  }
  strcat(path, "/table.csv");
  n = strlen(path);
  CHECK(n > 3600 && n < 4000);
  CHECK(egw_table_write(t, path, EGW_FORMAT_CSV) == EGW_OK);
  CHECK(egw_table_read(path, &r) == EGW_OK && r != NULL);
  egw_table_free(&r);
  /* beyond PATH_MAX */
  memset(path, 'x', 5000);
  memcpy(path, "build/", 6);
  strcpy(path + 5000, "_END_OF_THE_PATH.csv");
  n = strlen(path);
  CHECK(egw_table_write(t, path, EGW_FORMAT_CSV) == EGW_IO_ERROR);
  CHECK(strstr(last_message(), "_END_OF_THE_PATH.csv") != NULL);
  CHECK(strncmp(message, "path = build/xxxx", 17) == 0);
  CHECK(egw_table_read(path, &r) == EGW_IO_ERROR && r == NULL);
  CHECK(strstr(last_message(), "_END_OF_THE_PATH.csv") != NULL);
  {
    egw_scene s;
    egw_hysteresis h = NULL;
    egw_scene_default(&s);
    CHECK(egw_scene_read(path, &s) == EGW_IO_ERROR);
    CHECK(strstr(last_message(), "_END_OF_THE_PATH.csv") != NULL);
    CHECK(egw_hysteresis_read(path, &h) == EGW_IO_ERROR && h == NULL);
    CHECK(strstr(last_message(), "_END_OF_THE_PATH.csv") != NULL);
  }
  /* the units string of the LAMMPS writer goes through the same reader */
  CHECK(egw_tables_write_lammps_units(1, &t, "build/io_units.table", "") ==
        EGW_INVALID_ARGUMENT);
  CHECK(strncmp(last_message(), "units: empty", 12) == 0);
  egw_table_free(&t);
  return failures;
}
