!> The reference of the sigma 42 nm steel E-GW + cap impact at 3 m/s (example cap-bead-grid's
!> steel pair: R* = 0.5 mm, E = 210 GPa, nu 0.3, mu 4, p_y = 3.2 GPa, m* = m/2 of a 1 mm
!> bead; doc/stability.md "The sigma 42 nm steel impact: settled"). It runs `restitution`
!> at rel_tol 1e-6 for the turning point delta_m, loads the history at delta_m at rel_tol
!> HTOL, and then, at FRAC delta_m, unloads with the default route at rel_tol 1e-6, 1e-7,
!> 1e-8 and on fixed meshes of 257 ... 2049 nodes (n_radial: one level, no adaptive
!> steps; they reach past the rim of the history's plastic zone). Modes (third argument):
!>   sweep       the default route at 0.02, 0.04, ... 0.98 delta_m;
!>   fine        the default route at 0.560, 0.564, ... 0.752 delta_m;
!>   finefixed   the same on fixed meshes of 1025 nodes;
!>   work        W_unload by 8-point Gauss-Legendre on 20, 40, 80 equal panels of
!>               [0.36, 1] delta_m on fixed meshes of 513 and 1025 nodes, and
!>               e = sqrt(W_unload/(m* v**2/2)) (the turning point makes W_load = m* v**2/2).
!> Forces are printed scaled, P/(E* sqrt(R) sigma**1.5).
!>
!> Usage: fpm run --profile release --example steel-mid-unload -- [FRAC [HTOL [MODE]]]
!> (defaults 0.67, 1e-8; one thread: OMP_NUM_THREADS=1; `work` takes ~5-10 min).
program steel_mid_unload
   use egw, only: dp, contact_params, model_egw, solver_options, egw_error, restitution, &
      & first_yield_overlap, loading_history, load_history, solve_unload, solve_result
   use, intrinsic :: iso_fortran_env, only: int64
   implicit none
   real(dp), parameter :: pi = acos(-1.0_dp)
   type(contact_params) :: p
   type(solver_options) :: opts
   type(egw_error), allocatable :: err
   type(loading_history) :: hist
   type(solve_result) :: res, top
   real(dp) :: mass, e, diss, depth, dy, scale, frac, htol, unit_r
   integer :: i, k, ios
   integer, parameter :: ns(7) = [257, 385, 513, 769, 1025, 1537, 2049]
   real(dp), parameter :: tols(3) = [1.0e-6_dp, 1.0e-7_dp, 1.0e-8_dp]
   character(len=32) :: arg, mode
   integer(int64) :: c0, c1, rate

   p = contact_params(model=model_egw, radius=0.5e-3_dp, modulus=210.0e9_dp/(2.0_dp* &
      & (1.0_dp - 0.3_dp**2)), sigma=4.2e-8_dp, mu=4.0_dp, psi=0.0_dp, &
      & flow_pressure=3.2e9_dp)
   mass = 0.5_dp*7830.0_dp*4.0_dp*pi*1.0e-9_dp/3.0_dp
   dy = first_yield_overlap(p)
   scale = p%modulus*sqrt(p%radius)*p%sigma**1.5_dp
   unit_r = sqrt(p%radius*p%sigma)
   frac = 0.67_dp
   htol = 1.0e-8_dp
   mode = ""
   if (command_argument_count() >= 1) then
      call get_command_argument(1, arg)
      read (arg, *, iostat=ios) frac
   end if
   if (command_argument_count() >= 2) then
      call get_command_argument(2, arg)
      read (arg, *, iostat=ios) htol
   end if
   if (command_argument_count() >= 3) call get_command_argument(3, mode)

   opts%n_threads = 1
   opts%rel_tol = 1.0e-6_dp
   call system_clock(c0, rate)
   call restitution(p, opts, mass, 3.0_dp, e, diss, err, max_overlap=depth)
   call system_clock(c1)
   if (allocated(err)) error stop "restitution failed: "//err%message
   print '(a,f10.7,a,es24.16,a,f9.5,a,f7.1)', "e = ", e, " delta_m = ", depth, &
      & " delta_m/delta_y = ", depth/dy, " s ", real(c1 - c0)/real(rate)
   opts%rel_tol = htol
   call load_history(p, opts, depth, hist, top, err)
   if (allocated(err)) error stop "history failed: "//err%message
   print '(a,es10.2,a,es24.16,a,es10.2)', "history rel_tol ", htol, " P(delta_m)/scale ", &
      & top%force/scale, " est ", top%est_rel_err

   select case (mode)
   case ("work")
      call unloading_work()
   case ("sweep", "fine", "finefixed")
      hist%options%rel_tol = 1.0e-6_dp
      if (mode == "finefixed") hist%options%n_radial = 1025
      do k = 1, 49
         frac = real(k, dp)/50.0_dp
         if (mode /= "sweep") frac = 0.56_dp + 0.004_dp*real(k - 1, dp)
         call report("sweep", frac)
      end do
   case default
      do i = 1, size(tols)
         hist%options%rel_tol = tols(i)
         hist%options%n_radial = 0
         call report("adaptive", tols(i))
      end do
      do k = 1, size(ns)
         hist%options%rel_tol = 1.0e-6_dp
         hist%options%n_radial = ns(k)
         call report("n_radial", real(ns(k), dp))
      end do
   end select

contains

   !> One unloading solve at frac delta_m (sweeps: x = frac; else at FRAC, x labels it).
   subroutine report(label, x)
      character(len=*), intent(in) :: label
      real(dp), intent(in) :: x
      real(dp) :: at
      at = frac
      call system_clock(c0)
      call solve_unload(hist, at*depth, res, err)
      call system_clock(c1)
      if (allocated(err)) then
         print '(a,1x,es10.3,a,a)', label, x, " failed: ", err%message
         deallocate (err)
         return
      end if
      print '(a,1x,es10.3,a,es24.16,a,es10.2,a,f7.1,a,f12.6)', label, x, " P/scale ", &
         & res%force/scale, " est ", res%est_rel_err, " s ", real(c1 - c0)/real(rate), &
         & " a* ", res%contact_radius/unit_r
   end subroutine report

   !> W_unload by 8-point Gauss-Legendre on n_panel equal panels of [0.36, 1] delta_m, on
   !> fixed meshes of n_radial nodes (the force below 0.38 delta_m is < 1e-90 of the peak)
   subroutine unloading_work()
      real(dp), parameter :: x8(4) = [0.1834346424956498_dp, 0.5255324099163290_dp, &
         & 0.7966664774136267_dp, 0.9602898564975363_dp], w8(4) = [0.3626837833783620_dp, &
         & 0.3137066458778873_dp, 0.2223810344533745_dp, 0.1012285362903763_dp]
      integer, parameter :: panels(3) = [20, 40, 80], nodes(2) = [513, 1025]
      integer :: ip, jn, j, q, sgn
      real(dp) :: lo, h, mid, x, wsum, energy
      energy = 0.5_dp*mass*9.0_dp
      do jn = 1, size(nodes)
         do ip = 1, size(panels)
            hist%options%rel_tol = 1.0e-6_dp
            hist%options%n_radial = nodes(jn)
            lo = 0.36_dp*depth
            h = (depth - lo)/real(panels(ip), dp)
            wsum = 0.0_dp
            do j = 1, panels(ip)
               mid = lo + (real(j, dp) - 0.5_dp)*h
               do q = 1, 4
                  do sgn = -1, 1, 2
                     x = mid + real(sgn, dp)*0.5_dp*h*x8(q)
                     call solve_unload(hist, x, res, err)
                     if (allocated(err)) error stop "unloading failed: "//err%message
                     wsum = wsum + 0.5_dp*h*w8(q)*res%force
                  end do
               end do
            end do
            print '(a,i5,a,i4,a,es24.16,a,f12.9)', "n_radial ", nodes(jn), " panels ", &
               & panels(ip), " W_unload ", wsum, " e = sqrt(W_u/(m v^2/2)) ", &
               & sqrt(wsum/energy)
         end do
      end do
   end subroutine unloading_work

end program steel_mid_unload
