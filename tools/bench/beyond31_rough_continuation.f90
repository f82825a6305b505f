!> beyond31: how far the smooth fully capped law, matched at a rough + cap table's top X,
!> follows the rough + cap solves above X (issue 32; doc/benchmarks.md "Stop 65: beyond31").
!> Loading: P_c(d) = c P_s(d + s), P_s the smooth fully capped force (doc/theory.md §12,
!> d/delta_y = alpha^2/2 + k alpha, P_s = 2 alpha^2 P_u), s and c from P(X) and dP/dd(X)
!> of a solve at X. Unloading below m > X: P_c(d; m) = r^2 P_X(X - (m - d)/r), r =
!> alpha(m + s)/alpha(X + s), P_X the unloading curve of X (solves). Errors in P(m).
!> "flat-offset err": the variant not kept, the rough layer's offset D(u) = d(u p_y) -
!> d(p_y) of a uniformly loaded rough flat (flat_pressure) taken unscaled by r.
!> The survey of stop 65 (doc/benchmarks.md "Stop 65: beyond31"): for each line
!> "MODEL SIGMA/DY X/DY TOL" of E-GW, EP-GW (psi 1), GW at sigma/delta_y 0.01..1, X 35.
!> Build: gfortran -O2 -fopenmp -I build/gfortran_<mods> \
!>   tools/bench/beyond31_rough_continuation.f90 build/gfortran_<lib>/egw/libegw.a \
!>   -lfftw3_omp -lfftw3 -llapack -lblas -o /tmp/cont
!> Run:   /tmp/cont MODEL SIGMA_OVER_DY X_OVER_DY [rel_tol [F1,F2,F3]]   (MODEL: egw, epgw,
!>        gw; F: the m/X sampled, default 1.2,2,5)
program beyond31_rough_continuation
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error
   use egw_params, only: contact_params, model_egw, model_epgw, model_gw
   use egw_asperity, only: flat_pressure
   use egw_rough_sphere, only: solver_options, solve_result, loading_history, &
      & load_history, solve_unload
   implicit none
   real(dp), parameter :: radius = 1.0e-3_dp, modulus = 1.0e11_dp, py = 1.0e9_dp
   real(dp), parameter :: k = 8.0_dp/pi**2
   real(dp) :: factors(3) = [1.2_dp, 2.0_dp, 5.0_dp]
   integer, parameter :: n_u = 12
   type(contact_params) :: p
   type(solver_options) :: opt
   type(loading_history) :: hist
   type(solve_result) :: top, res
   type(egw_error), allocatable :: err
   character(len=16) :: arg
   real(dp) :: dy, pu, x, px, kx, s, c, m, pm, r, d, pc, kc, t, worst_load, worst_unload, &
      & ratio_x, lo, hi, mid, du(n_u), pxu(n_u), kxu(n_u), resid_x, t0, t1, sig, dx_flat, d_alt, worst_alt
   integer :: model, i, j
   call get_command_argument(1, arg)
   select case (trim(arg))
   case ("epgw"); model = model_epgw
   case ("gw"); model = model_gw
   case default; model = model_egw
   end select
   dy = (pi*py/(2*modulus))**2*radius
   pu = modulus*sqrt(radius)*dy**1.5_dp
   call get_command_argument(2, arg); read (arg, *) sig
   call get_command_argument(3, arg); read (arg, *) x
   x = x*dy
   opt = solver_options(rel_tol=1.0e-7_dp)
   if (command_argument_count() >= 4) then
      call get_command_argument(4, arg); read (arg, *) t
      opt = solver_options(rel_tol=t)
   end if
   if (command_argument_count() >= 5) then
      call get_command_argument(5, arg); read (arg, *) factors
   end if
   p = contact_params(model=model, radius=radius, modulus=modulus, sigma=sig*dy, mu=4.0_dp, &
      & flow_pressure=py)
   if (model == model_epgw) p%psi = 1.0_dp
   call cpu_time(t0)
   call load_history(p, opt, x, hist, top, err)
   if (allocated(err)) error stop "load_history X: "//err%message
   call cpu_time(t1)
   px = top%force
   kx = top%stiffness
   print '(a, es10.3, a, f8.2, a, es16.8, a, es16.8, a, f8.2, a)', "sigma/dy", sig, " X/dy", &
      & x/dy, " P(X)/Pu", px/pu, " K(X)dy/Pu", kx*dy/pu, " (", t1 - t0, " s)"
   ! s: P_s/P_s' at X + s equals P(X)/K(X) (monotone in s: bisection), then c
   ratio_x = px/kx
   lo = -0.5_dp*x
   hi = 0.5_dp*x
   do i = 1, 200
      mid = 0.5_dp*(lo + hi)
      if (smooth_force(x + mid)/smooth_stiffness(x + mid) < ratio_x) then
         lo = mid
      else
         hi = mid
      end if
   end do
   s = 0.5_dp*(lo + hi)
   c = px/smooth_force(x + s)
   print '(a, es14.6, a, es14.6, a, es14.6)', "shift s/sigma", s/p%sigma, " s/dy", s/dy, &
      & " scale c-1", c - 1
   ! the unloading curve of X at n_u points, (X - d)/X = t^2 stretched toward separation
   do j = 1, n_u
      t = real(j - 1, dp)/(n_u - 1)
      du(j) = x - (x*0.12_dp)*t**2 - 6*p%sigma*t
      call solve_unload(hist, du(j), res, err)
      if (allocated(err)) error stop "solve_unload X: "//err%message
      pxu(j) = res%force
      kxu(j) = res%stiffness
   end do
   do i = 1, size(factors)
      m = factors(i)*x
      call cpu_time(t0)
      call load_history(p, opt, m, hist, top, err)
      if (allocated(err)) error stop "load_history m: "//err%message
      call cpu_time(t1)
      pm = top%force
      pc = c*smooth_force(m + s)
      kc = c*smooth_stiffness(m + s)
      worst_load = abs(pc - pm)/pm
      print '(a, f5.1, a, es11.3, a, es11.3, a, es11.3, a, f7.1, a)', " m/X", factors(i), &
         & " loading (Pc-P)/P(m)", (pc - pm)/pm, "  (Kc-K)/K", (kc - top%stiffness)/ &
         & top%stiffness, "  uncorrected c=1,s=0:", (smooth_force(m) - pm)/pm, " (", &
         & t1 - t0, " s)"
      r = alpha(m + s)/alpha(x + s)
      worst_unload = 0
      worst_alt = 0
      dx_flat = flat_separation(py)
      do j = 1, n_u
         d = m - (x - du(j))*r
         call solve_unload(hist, d, res, err)
         if (allocated(err)) error stop "solve_unload m: "//err%message
         pc = r*r*pxu(j)
         resid_x = (pc - res%force)/pm
         worst_unload = max(worst_unload, abs(resid_x))
         ! the rough layer's offset D(u) taken as a uniform flat's, not scaled by r
         t = flat_separation(max(pxu(j)/px, 1.0e-300_dp)*py) - dx_flat
         d_alt = m - r*((x - du(j)) - t) - t
         call solve_unload(hist, d_alt, res, err)
         if (allocated(err)) error stop "solve_unload alt: "//err%message
         worst_alt = max(worst_alt, abs(pc - res%force)/pm)
         print '(a, f9.5, a, es11.3, a, es11.3, a, es11.3, a, es11.3)', "   (m-d)/m", &
            & (m - d)/m, " P/P(m)", pc/pm, " err/P(m)", resid_x, " flat-offset err", &
            & (pc - res%force)/pm, " D/sigma", t/p%sigma
      end do
      print '(a, f5.1, a, es11.3, a, es11.3)', " m/X", factors(i), " worst load", &
         & worst_load, " worst unload", worst_unload, " flat offset", worst_alt
   end do
contains
   !> the separation of the rough flat of p under a uniform pressure q (bisection)
   real(dp) function flat_separation(q) result(h)
      real(dp), intent(in) :: q
      real(dp) :: a, b, f, df
      integer :: it
      a = -10*p%sigma
      b = 20*p%sigma
      do it = 1, 200
         h = 0.5_dp*(a + b)
         call flat_pressure(p, h, f, df, err)
         if (f > q) then
            a = h
         else
            b = h
         end if
      end do
   end function flat_separation
   pure real(dp) function alpha(d)
      real(dp), intent(in) :: d
      alpha = sqrt(k*k + 2*(d/dy)) - k
   end function alpha
   pure real(dp) function smooth_force(d)
      real(dp), intent(in) :: d
      smooth_force = 2*alpha(d)**2*pu
   end function smooth_force
   pure real(dp) function smooth_stiffness(d)
      real(dp), intent(in) :: d
      smooth_stiffness = 4*alpha(d)/(alpha(d) + k)*pu/dy
   end function smooth_stiffness
end program beyond31_rough_continuation
