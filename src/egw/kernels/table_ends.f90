!> The laws at the ends of a force table (doc/theory.md §9): the separated tail of a rough
!> sphere, the rigid-sphere law far apart, and the deep-overlap asymptote, Hertz's force on
!> the overlap the rough layer leaves. Closed forms matched to a table's end node;
!> egw_table and egw_table_universal continue their interpolants above delta_max with the
!> deep law; below a rough table's cut-off they give 0, and the tail law serves the
!> builders that need the force's continuation there (hysteresis gaps).
module egw_table_ends
   use, intrinsic :: iso_c_binding, only: c_double
   use egw_kinds, only: dp
   use egw_gauss, only: gauss_f32, gauss_f52
   implicit none
   private

   public :: tail_force, deep_force, deep_energy, deep_radius_factor, deep_reach
   public :: deep_law, deep_law_fit, deep_law_force, deep_law_energy, deep_law_radius_factor

   !> deep_force's law fitted once to a table's last node (deep_law_fit), so that an
   !> evaluation above it costs a cube root and a square root, not five powers: a contact
   !> far above a table's end (sigma -> 0, e.g. 1e-16 in a LAMMPS deck converted from
   !> Hertz) is evaluated there at every step.
   type :: deep_law
      logical :: ready = .false.   !< fitted (deep_law_fit was called)
      logical :: ok = .false.      !< the law applies (else the linear continuation)
      real(dp) :: d_e = 0, p_e = 0, k_e = 0   !< the last node, its force and stiffness
      real(dp) :: t_e = 0, a = 0, u_0 = 0     !< deep_fit's constants
   end type deep_law

   interface
      !> C99's cube root (libm): a few times cheaper than x**(1/3), and exact for cubes
      pure function libm_cbrt(x) result(y) bind(C, name="cbrt")
         import :: c_double
         real(c_double), value, intent(in) :: x
         real(c_double) :: y
      end function libm_cbrt
   end interface

contains

   !> The separated tail of a rough sphere below the cut-off delta_c (doc/theory.md §9).
   !> Far apart the sphere barely deforms, so the force is that of a rigid sphere on the
   !> rough flat, P = 2 pi R int_{-delta}^inf p_G(d) dd; with elastic Gaussian summits
   !> (p_G proportional to F_{3/2}(d/sigma)) this is
   !>   P = (2/5) pi sqrt(R/2) mu E* sigma^(3/2) F_{5/2}(-delta/sigma)
   !> (solves agree to 2e-5 at -4 sigma, 2e-7 at -5 sigma, 5e-10 at -6 sigma for mu = 4).
   !> Matched to the table's first node (p_c, k_c):
   !>   P = p_c F_{5/2}(h)/F_{5/2}(h_c) exp(kappa (delta - delta_c)),  h = -delta/sigma.
   !> Elastic summits: kappa = 0, the rigid-sphere law itself (its slope at delta_c meets
   !> k_c to the solver's accuracy). Plastic summits (EP-GW, psi > 0), many of which yield
   !> even far apart: kappa = k_c/p_c - (5/2) F_{3/2}(h_c)/(sigma F_{5/2}(h_c)) matches
   !> the slope too. C1 at delta_c, 0 as delta -> -inf, and exactly 0 for delta <=
   !> -40 sigma (F_{5/2} is 0 there).
   pure subroutine tail_force(delta_c, p_c, k_c, sigma, plastic, delta, force, stiffness)
      real(dp), intent(in) :: delta_c   !< cut-off, the table's first node [length]
      real(dp), intent(in) :: p_c, k_c  !< force and stiffness there
      real(dp), intent(in) :: sigma     !< summit height deviation [length], > 0
      logical, intent(in) :: plastic    !< summits yield (EP-GW with psi > 0)
      real(dp), intent(in) :: delta     !< overlap [length], < delta_c
      real(dp), intent(out) :: force, stiffness   !< force [force] and stiffness dP/ddelta at delta
      real(dp) :: f52_c, kappa
      call tail_constants(delta_c, p_c, k_c, sigma, plastic, f52_c, kappa)
      call tail_force_matched(delta_c, p_c, sigma, f52_c, kappa, delta, force, stiffness)
   end subroutine tail_force

   !> tail_force's constants of the match at the cut-off, which a table computes once:
   !> f52_c = F_{5/2}(h_c) and kappa (0 where the law does not apply).
   pure subroutine tail_constants(delta_c, p_c, k_c, sigma, plastic, f52_c, kappa)
      real(dp), intent(in) :: delta_c, p_c, k_c, sigma   !< as tail_force
      logical, intent(in) :: plastic                     !< as tail_force
      real(dp), intent(out) :: f52_c   !< F_{5/2}(-delta_c/sigma)
      real(dp), intent(out) :: kappa   !< exponent rate of the match [1/length]
      f52_c = gauss_f52(-delta_c/sigma)
      kappa = 0.0_dp
      if (plastic .and. p_c > 0.0_dp .and. f52_c > 0.0_dp) &
         & kappa = k_c/p_c - 2.5_dp*gauss_f32(-delta_c/sigma)/(sigma*f52_c)
   end subroutine tail_constants

   !> tail_force from tail_constants' f52_c and kappa (the same values, one F_{5/2} fewer
   !> per call, and no F_{3/2} at the cut-off).
   pure subroutine tail_force_matched(delta_c, p_c, sigma, f52_c, kappa, delta, force, &
      & stiffness)
      real(dp), intent(in) :: delta_c, p_c, sigma   !< as tail_force
      real(dp), intent(in) :: f52_c, kappa          !< tail_constants'
      real(dp), intent(in) :: delta                 !< overlap [length], < delta_c
      real(dp), intent(out) :: force, stiffness
      real(dp) :: f52, log_p
      force = 0.0_dp
      stiffness = 0.0_dp
      f52 = gauss_f52(-delta/sigma)
      if (.not. (p_c > 0.0_dp .and. f52_c > 0.0_dp .and. f52 > 0.0_dp)) return
      log_p = log(p_c) + log(f52/f52_c) + kappa*(delta - delta_c)
      if (.not. log_p > log(tiny(1.0_dp))) return
      force = exp(min(log_p, log(p_c)))
      stiffness = force*(2.5_dp*gauss_f32(-delta/sigma)/(sigma*f52) + kappa)
   end subroutine tail_force_matched

   !> Deep overlaps above the last node d_e (force p_e, stiffness k_e), doc/theory.md §9:
   !> the model's asymptote, Hertz's force on the overlap g the rough layer leaves,
   !>   P = c g^(3/2),  delta = d_e + (g - g_e) + a (g^(1/3) - g_e^(1/3)),
   !> with c = (4/3) E sqrt(R), the Hertz constant every model tends to (exact, not
   !> fitted), g_e = (p_e/c)^(2/3), and a fitted so that K = k_e at d_e (C1). The
   !> g^(1/3) term is classic GW's layer compression (its central summit interference
   !> grows as (p_0/C)^(2/3) ~ delta^(1/3), DESIGN eq. 20 corrected); for E-GW and EP-GW a
   !> is small and absorbs the decaying corrections. Increasing (d delta/dg > 0 at d_e
   !> and growing), exact for Hertz (a = 0). Against solves up to 1e6 sigma from d_e = 20
   !> sigma: classic GW within 0.2 % (0.1 <= mu <= 1e5), E-GW and EP-GW 0.07 %; within 1 %
   !> from d_e = 10 sigma (GW, mu >= 0.1) and 2 sigma (E-GW, EP-GW; test_deep_law).
   !> Where p_e, k_e or c is not positive, the linear continuation.
   pure subroutine deep_force(d_e, p_e, k_e, c, delta, force, stiffness)
      real(dp), intent(in) :: d_e        !< last node [length]
      real(dp), intent(in) :: p_e, k_e   !< force and stiffness there
      real(dp), intent(in) :: c          !< Hertz constant (4/3) E sqrt(R) [force/length^1.5]
      real(dp), intent(in) :: delta      !< overlap [length], >= d_e
      real(dp), intent(out) :: force, stiffness   !< force [force] and stiffness dP/ddelta at delta
      call deep_law_force(deep_law_fit(d_e, p_e, k_e, c), delta, force, stiffness)
   end subroutine deep_force

   !> deep_force's law fitted to the last node (d_e, p_e, k_e) with Hertz constant c,
   !> for deep_law_force (deep_force gives the same values bit for bit).
   pure function deep_law_fit(d_e, p_e, k_e, c) result(law)
      real(dp), intent(in) :: d_e, p_e, k_e, c   !< as deep_force
      type(deep_law) :: law
      law%ready = .true.
      law%d_e = d_e
      law%p_e = p_e
      law%k_e = k_e
      call deep_fit(p_e, k_e, c, law%t_e, law%a, law%u_0, law%ok)
   end function deep_law_fit

   !> deep_force at delta >= law%d_e with the fitted law: P = p_e q^(9/2), q = t/t_e
   !> (q^4 sqrt(q): no power function).
   pure subroutine deep_law_force(law, delta, force, stiffness)
      type(deep_law), intent(in) :: law   !< fitted by deep_law_fit
      real(dp), intent(in) :: delta      !< overlap [length], >= law%d_e
      real(dp), intent(out) :: force, stiffness   !< force [force] and stiffness dP/ddelta at delta
      real(dp) :: t, q, q2
      if (law%ok) then
         t = deep_root(law%t_e, law%a, law%u_0, delta - law%d_e)
         q = t/law%t_e
         q2 = q*q
         force = law%p_e*(q2*q2)*sqrt(q)
         ! dP/ddelta = (dP/dg)/(ddelta/dg) = 1.5 P/(t^3 + (a/3) t); u_0 at t_e
         stiffness = 1.5_dp*force/(t*(t*t + law%a/3))
      else
         stiffness = law%k_e
         force = law%p_e + law%k_e*(delta - law%d_e)
      end if
   end subroutine deep_law_force

   !> Work int_{d_e}^{delta} P of deep_force's law: with P = p_e (t/t_e)^(9/2) and
   !> ddelta = (3 t^2 + a) dt, p_e [3 t_e^3 (q^7.5 - 1)/7.5 + a t_e (q^5.5 - 1)/5.5],
   !> q = t/t_e; the linear continuation's where deep_force uses it.
   pure real(dp) function deep_energy(d_e, p_e, k_e, c, delta) result(energy)
      real(dp), intent(in) :: d_e, p_e, k_e, c   !< as deep_force
      real(dp), intent(in) :: delta              !< overlap [length], >= d_e
      energy = deep_law_energy(deep_law_fit(d_e, p_e, k_e, c), delta)
   end function deep_energy

   !> deep_energy with the fitted law (the same values bit for bit; q^5 sqrt(q), no
   !> power function).
   pure real(dp) function deep_law_energy(law, delta) result(energy)
      type(deep_law), intent(in) :: law   !< fitted by deep_law_fit
      real(dp), intent(in) :: delta   !< overlap [length], >= law%d_e
      real(dp) :: q, q5, rq
      if (law%ok) then
         q = deep_root(law%t_e, law%a, law%u_0, delta - law%d_e)/law%t_e
         rq = sqrt(q)
         q5 = (q*q)*(q*q)*q*rq                    ! q^5.5
         energy = law%p_e*(3*law%t_e**3*(q5*q*q - 1)/7.5_dp + law%a*law%t_e*(q5 - 1)/5.5_dp)
      else
         energy = law%p_e*(delta - law%d_e) + 0.5_dp*law%k_e*(delta - law%d_e)**2
      end if
   end function deep_law_energy

   !> The factor sqrt(g/g_e) by which deep_force's law grows the contact radius (Hertz's
   !> a = sqrt(R g) on the layer's overlap g); 1 + (delta - d_e) k_e/(2 p_e) where
   !> deep_force is linear.
   pure real(dp) function deep_radius_factor(d_e, p_e, k_e, c, delta) result(factor)
      real(dp), intent(in) :: d_e, p_e, k_e, c   !< as deep_force
      real(dp), intent(in) :: delta              !< overlap [length], >= d_e
      factor = deep_law_radius_factor(deep_law_fit(d_e, p_e, k_e, c), delta)
   end function deep_radius_factor

   !> deep_radius_factor with the fitted law (the same values bit for bit).
   pure real(dp) function deep_law_radius_factor(law, delta) result(factor)
      type(deep_law), intent(in) :: law   !< fitted by deep_law_fit
      real(dp), intent(in) :: delta   !< overlap [length], >= law%d_e
      real(dp) :: q
      factor = 1.0_dp
      if (law%ok) then
         q = deep_root(law%t_e, law%a, law%u_0, delta - law%d_e)/law%t_e
         factor = q*sqrt(q)
      else if (law%p_e > 0.0_dp) then
         factor = max(1.0_dp, 1.0_dp + (delta - law%d_e)*law%k_e/(2*law%p_e))
      end if
   end function deep_law_radius_factor

   !> The overlap where deep_force's force reaches p_lim (>= p_e): closed form in g,
   !> delta = d_e + (g - g_e) + a (g^(1/3) - g_e^(1/3)), g = g_e (p_lim/p_e)^(2/3). The
   !> callers bound their arguments with it so that forces stay doubles. Formed in logs:
   !> p_lim/p_e overflows for p_lim near huge (then the a term, O(g^(1/3)), is dropped
   !> against g, and where g itself leaves the doubles, c g^1.5 stays below p_lim for
   !> every double: huge/4).
   pure real(dp) function deep_reach(d_e, p_e, k_e, c, p_lim) result(delta)
      real(dp), intent(in) :: d_e, p_e, k_e, c   !< as deep_force
      real(dp), intent(in) :: p_lim              !< force [force], >= p_e
      real(dp) :: t_e, a, u_0, q, g, log_g
      logical :: ok
      call deep_fit(p_e, k_e, c, t_e, a, u_0, ok)
      if (ok) then
         log_g = 2*(log(p_lim) - log(c))/3
         if (log_g > log(0.25_dp*huge(1.0_dp))) then
            delta = 0.25_dp*huge(1.0_dp)
            return
         end if
         g = exp(log_g)
         q = exp((log(p_lim) - log(p_e))/4.5_dp)
         delta = d_e + (g - t_e**3) + a*t_e*(q - 1)
         if (.not. (abs(delta) <= huge(1.0_dp))) delta = d_e + g
      else
         delta = d_e + (p_lim - p_e)/max(k_e, tiny(1.0_dp))
      end if
   end function deep_reach

   !> deep_force's fit: t_e = g_e^(1/3), a, u_0 = 1.5 p_e/k_e (= t_e^3 + a t_e/3, the
   !> condition K = k_e at d_e). False where the law does not apply (p_e, k_e, c not
   !> positive, or not doubles): ok = .false.
   pure subroutine deep_fit(p_e, k_e, c, t_e, a, u_0, ok)
      real(dp), intent(in) :: p_e, k_e, c
      real(dp), intent(out) :: t_e, a, u_0
      logical, intent(out) :: ok
      t_e = 0.0_dp
      a = 0.0_dp
      u_0 = 0.0_dp
      ok = p_e > 0.0_dp .and. k_e > 0.0_dp .and. c > 0.0_dp .and. p_e <= huge(1.0_dp) &
         & .and. k_e <= huge(1.0_dp) .and. c <= huge(1.0_dp)
      if (.not. ok) return
      ! (p_e/c)^(2/9) without forming p_e/c, which can leave the doubles where g cannot
      t_e = (p_e**(1.0_dp/3)/c**(1.0_dp/3))**(2.0_dp/3)
      u_0 = 1.5_dp*p_e/k_e
      a = 3*(u_0 - t_e**3)/t_e
      ok = t_e > 0.0_dp .and. t_e <= huge(1.0_dp) .and. u_0 > 0.0_dp .and. &
         & u_0 <= huge(1.0_dp) .and. abs(a) <= huge(1.0_dp)
   end subroutine deep_fit

   !> The root t >= t_e of f(t) = (t - t_e)(t^2 + t t_e + t_e^2 + a) - s (s = delta - d_e
   !> >= 0), i.e. t^3 + a t = t_e^3 + a t_e + s: f is convex for t > 0 and increasing from
   !> t_e (f'(t_e) = 3 u_0/t_e > 0), so Newton converges from either side (from below, the
   !> first step lands above the root, then the steps descend onto it). Start: the smaller
   !> of the tangent at t_e (an upper bound, close for small s) and c - a/(3c), c =
   !> cbrt(t_e^3 + a t_e + s) (at least t_e): the root itself when a = 0 (Hertz), and
   !> within (a/(3 t^2))^2 of t otherwise, which deep overlaps make far below round-off,
   !> so that the first Newton step there only confirms it.
   pure real(dp) function deep_root(t_e, a, u_0, s) result(t)
      real(dp), intent(in) :: t_e, a, u_0, s
      real(dp) :: f, step, c
      integer :: it
      t = t_e
      if (.not. s > 0.0_dp) return
      c = libm_cbrt(t_e**3 + a*t_e + s)
      t = min(t_e + s*t_e/(3*u_0), max(c - a/(3*c), t_e))
      do it = 1, 200
         f = (t - t_e)*(t*t + t*t_e + t_e*t_e + a) - s
         step = f/(3*t*t + a)
         if (.not. abs(step) > 4*epsilon(t)*t) exit   ! at the root (to round-off)
         t = t - step
      end do
      t = max(t, t_e)
   end function deep_root

end module egw_table_ends
