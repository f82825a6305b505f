/*
 * egw_hysteresis_eval_state (include/egw.h), a DEM code's per-contact call. The steps its
 * state answers alone on the routes of a separated or touching EP-GW contact are answered
 * here, in C, before any stack frame: a zero piece (beyond the loading cut-off), a
 * folded piece of the separated tail (exp of one cubic), a log-ratio piece on a linear
 * loading interval (in contact: P e^-h), and loading further inside the state's loading
 * interval. Every other step, and any these decline, goes on to the Fortran entry
 * egw_hysteresis_eval_state_general (capi_hysteresis.f90: its own served steps, then
 * the checked full evaluation), which gives what they decline the same bits. The
 * arithmetic is egw_capi_hysteresis's eval_state_served's (and egw.h's inline
 * egw_hysteresis_eval_cached's), in the same order, the log-ratio pieces' exp egw.h's
 * egw_piece_exp_ (= piece_exp): the same bits, and the same state left (tests
 * hysteresis "C eval_state = hysteresis_eval_state, separated", "served steps: the C top =
 * the Fortran entry = hysteresis_eval_state, bit for bit" and unload_checks.c). One of the
 * served arithmetic's four copies (src/egw/capi/README.md: a change goes into all four).
 * Why in C: in Fortran the call cost 2.1x an inline Hertz formula beyond the cut-off and
 * 6.1-6.5x in the tail, where issue 33 item 5 asks 2x and 5x (doc/benchmarks.md "Stop
 * 57: callcost").
 *
 * The handle points to egw_capi_hysteresis's bind(C) hysteresis_handle (mirrored below):
 * the numbers of the table these steps read, so that they read no Fortran descriptor.
 *
 * Not an API of its own: egw_hysteresis_state_step is exported for the tests only.
 */
/* fpm compiles C without optimization flags; and no FMA contraction (the cubics' bits,
 * as egw.h asks of a caller of its inline) */
#if defined(__GNUC__) && !defined(__clang__)
#if !defined(__OPTIMIZE__)
#pragma GCC optimize("O2")
#endif
#pragma GCC optimize("fp-contract=off")
#endif

#include <float.h>
#include <stdint.h>
#include "egw.h"

/* (inlined here too: under the pragma gcc calls a plain static inline out of line) */
static inline EGW_ALWAYS_INLINE_ double egw_piece_exp_core_(double x);
static inline EGW_ALWAYS_INLINE_ double egw_piece_exp_(double x);

/* egw_capi_hysteresis's hysteresis_handle (bind(C): the same layout). */
struct egw_hysteresis_s {
  double tag;          /* the tag the table writes into its states (state[2]) */
  double served_limit; /* min(delta_max, input limit): a larger history or overlap, the call */
  double cutoff;       /* the loading table's cut-off */
  void *table;         /* the Fortran hysteresis_table */
};

/* The Fortran entry (capi_hysteresis.f90): every step this file does not answer, with the
 * table itself (NULL for a NULL handle: no indirection on its own served steps). */
int egw_hysteresis_eval_state_general(void *table, double delta,
                                      double state[EGW_HYSTERESIS_STATE_SIZE],
                                      double *force, double *stiffness);

/* The library's zero_lo (hysteresis_data.f90): -sqrt(DBL_MAX)/4, where zero pieces and
 * zero loading intervals start */
#define EGW_ZERO_LO_ (-3.351951982485649e+153)

/* The bits of a double: equal bits are equal doubles but for NaN, and the tag, zero_lo
 * and 3.0 compared so are never NaN (one integer compare, where ucomisd branches twice;
 * beyond the cut-off 1.76-1.78x Hertz against 1.83-1.87x, stop 57) */
static inline EGW_ALWAYS_INLINE_ uint64_t bits_of(double x)
{
  uint64_t b;
  memcpy(&b, &x, sizeof b);
  return b;
}

/* The bits of a double as a signed integer: below those of -708.0 exactly for x in
 * (-708, -0] (x with its sign bit set is INT64_MIN plus |x|'s bits, which order the
 * magnitudes, a NaN's above infinity's; +0 and positive x are not negative) */
static inline EGW_ALWAYS_INLINE_ int64_t signed_bits_of(double x)
{
  int64_t b;
  memcpy(&b, &x, sizeof b);
  return b;
}

/* The routes are eval_state_served's, tested in its order (a zero piece, a folded piece,
 * another piece, loading), each with its conditions: the state is h's (its tag); a
 * piece's turning point is the history, the piece covers delta and the history is at most
 * delta_max and the input limit; loading further (delta >= the history) stays inside the
 * state's loading interval, at most delta_max and the input limit, on the cut-off's side
 * the interval is. Where the full call's status would not be EGW_OK or its values not
 * finite, the Fortran entry's. Both outputs must be given (one test here, none at the
 * stores).
 * piece_step: 1 and the force and stiffness where a piece answers delta; 0 (nothing
 * written) where the Fortran entry must; -1 where no piece covers delta: loading_step's.
 * - A zero piece (state[10] = zero_lo; (state[10], state[11]]): +0 and +0.
 * - A folded piece (state[23] = 3; (state[10], state[11]], its end included: the step
 *   back at the history exactly is the piece's, stop 60): its cubic f and slope k, then
 *   exp(f) and exp(f) k. Served here where -708 < f <= -0 and |k| < 2^1023: exp(f) <= 1,
 *   so the stiffness is finite without a test after the exp, at the end of the step's
 *   dependency chain (0.8 ns a step there, stop 57); f's range is one compare of its bits
 *   (two of the double took 0.27 ns more a step, stop 58). A positive f or +0 (a tail
 *   force of 1 or above in the caller's units) takes the Fortran entry, which serves it
 *   with the same bits.
 * - A log-ratio piece on a linear loading interval (state[23] < 0; inside both): the
 *   loading force P times exp(-h), h the piece's cubic; a positive force with finite
 *   values (else the Fortran entry: zeros, or its refusal).
 * (Inlined into egw_hysteresis_eval_state, which then needs no stack frame on these
 * routes: loading_step, with its libm call, is in loading_or_general, out of line; the
 * tail's call 0.94 of the time, stop 58.) */
static inline EGW_ALWAYS_INLINE_ int piece_step(egw_hysteresis h, double delta,
                                                double *state, double *force,
                                                double *stiffness)
{
  double f, k;
  if (EGW_UNLIKELY_(!(h && state && force && stiffness))) return 0;
  if (EGW_UNLIKELY_(bits_of(state[2]) != bits_of(h->tag))) return 0;
  /* (the turning point compared by its bits too: equal bits are equal doubles or a NaN
   * history, which the limit refuses; -0 against +0 declined, the Fortran entry's) */
  if (EGW_LIKELY_(bits_of(state[1]) == bits_of(state[0]) && state[10] < delta &&
                  state[0] <= h->served_limit)) {
    if (bits_of(state[10]) == bits_of(EGW_ZERO_LO_)) {
      if (EGW_LIKELY_(delta <= state[11])) {
        *force = 0.0;
        *stiffness = 0.0;
        return 1;
      }
    } else if (EGW_LIKELY_(delta <= state[11])) {
      double x = delta - state[10], x2 = x * x;
      f = (state[13] + x * state[14]) + x2 * (state[15] + x * state[16]);
      k = (state[14] + 2 * x * state[15]) + 3 * x2 * state[16];
      if (EGW_LIKELY_(bits_of(state[23]) == bits_of(3.0))) {
        if (EGW_LIKELY_(signed_bits_of(f) < signed_bits_of(-708.0) &&
                        fabs(k) < 0x1p1023)) {
          f = egw_piece_exp_core_(f);
          *force = f;
          *stiffness = f * k;
          return 1;
        }
        return 0;
      }
      /* (the other pieces are open at their end: there the loading route's) */
      if (!(delta < state[11])) return -1;
      if (state[23] < 0.0 && state[17] <= delta && delta < state[18]) {
        double t = delta - state[17], t2 = t * t, p;
        double v = (state[19] + t * state[20]) + t2 * (state[21] + t * state[22]);
        double d = (state[20] + 2 * t * state[21]) + 3 * t2 * state[22];
        p = egw_piece_exp_(f);
        k = p * (d + v * k);
        f = v * p;
        if (EGW_LIKELY_(f > 0.0 && fabs(k) + f <= DBL_MAX)) {
          *force = f;
          *stiffness = k;
          return 1;
        }
      }
      return 0;   /* (the other pieces that cover delta: the Fortran entry's) */
    }
  }
  return -1;
}

/* 1 and the force and stiffness, and the state, where delta loads the contact further
 * (or is back at the history) inside the state's loading interval: the interval's cubic
 * (its exp on a ln P interval, state[23] > 0; 0 on a zero interval below the cut-off);
 * beyond the history the piece is dropped and the history moved to delta (at it exactly,
 * nothing changed). Else 0 and nothing written. For a step piece_step left (-1: h,
 * state and the outputs given, the tag h's). */
static inline EGW_ALWAYS_INLINE_ int loading_step(egw_hysteresis h, double delta,
                                                  double *state, double *force,
                                                  double *stiffness)
{
  double f, k;
  if (!(delta >= state[0] && state[17] <= delta && delta < state[18] &&
        delta <= h->served_limit))
    return 0;
  if (bits_of(state[17]) == bits_of(EGW_ZERO_LO_)) {
    if (!(delta < h->cutoff)) return 0;
    f = k = 0.0;
  } else {
    double t = delta - state[17], t2 = t * t, v, d;
    if (!(delta > h->cutoff)) return 0;
    v = (state[19] + t * state[20]) + t2 * (state[21] + t * state[22]);
    d = (state[20] + 2 * t * state[21]) + 3 * t2 * state[22];
    if (state[23] > 0.0) {
      f = exp(v);
      k = f * d;
    } else {
      f = v;
      k = d;
    }
  }
  if (!(fabs(f) <= DBL_MAX && fabs(k) <= DBL_MAX)) return 0;
  if (!(delta == state[0])) state[10] = state[11] = NAN;
  state[0] = delta;
  *force = f;
  *stiffness = k;
  return 1;
}

/* 1 where the state answers delta alone (egw_hysteresis_eval_state's C routes), else 0
 * and nothing written. */
static int state_step(egw_hysteresis h, double delta, double *state, double *force,
                      double *stiffness)
{
  int served = piece_step(h, delta, state, force, stiffness);
  if (served >= 0) return served;
  return loading_step(h, delta, state, force, stiffness);
}

#if defined(__GNUC__)
#define EGW_NOINLINE_ __attribute__((noinline))
#else
#define EGW_NOINLINE_
#endif

/* egw_hysteresis_eval_state where no piece covers delta: loading_step (inlined here: 18
 * instructions fewer on a step back at the history, stop 58, where the piece there is not
 * folded), else the Fortran entry (h given) */
static EGW_NOINLINE_ int loading_or_general(egw_hysteresis h, double delta, double *state,
                                            double *force, double *stiffness)
{
  if (loading_step(h, delta, state, force, stiffness)) return EGW_OK;
  return egw_hysteresis_eval_state_general(h->table, delta, state, force, stiffness);
}

int egw_hysteresis_eval_state(egw_hysteresis h, double delta,
                              double state[EGW_HYSTERESIS_STATE_SIZE], double *force,
                              double *stiffness)
{
  int served = piece_step(h, delta, state, force, stiffness);
  if (EGW_LIKELY_(served > 0)) return EGW_OK;
  if (served < 0) return loading_or_general(h, delta, state, force, stiffness);
  return egw_hysteresis_eval_state_general(h ? h->table : NULL, delta, state, force,
                                           stiffness);
}

/* state_step for the tests: 1 where egw_hysteresis_eval_state answered the step here. */
int egw_hysteresis_state_step(egw_hysteresis h, double delta,
                              double state[EGW_HYSTERESIS_STATE_SIZE], double *force,
                              double *stiffness)
{
  return state_step(h, delta, state, force, stiffness);
}
