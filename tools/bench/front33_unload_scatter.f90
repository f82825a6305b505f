!> How accurate a rough + cap table's unloading solves are near the force's front, relative
!> to the local force, and what tighter ones cost (issue 33 item 5; doc/benchmarks.md
!> "Stop 67: front33"). README's E-GW + cap scene, or with EGW_PROBE_MODEL = GW its GW + cap
!> (rough_cap_local_decompose's contact_params; R = 405284.734569351 effective, delta_y =
!> 100 sigma). The table at TOL is built once, only to place the overlaps: at each turning
!> point m, the overlaps where its force is u P(m) for u = 3e-2 .. 5e-4 (12 values, m
!> downwards), plus any given with @. There, against a reference (history and unloading
!> solve at REF, no law table; a failure retried at 10 REF, counted), the unloading solves
!> of the build's kind (load_history with the table's ZMC law, stiffness = .false.) at
!> solve tolerances TOLS (solver_options%rel_tol), each
!>   hist = curve: history at the build's curve tolerance (curve_options(., TOL)), the
!>                 unloading solves at tol (history%options%rel_tol set after loading),
!>   hist = same:  history and solves at tol,
!>   hist = hist:  history at tol, the unloading solves at the build's curve tolerance,
!> and each solve cold (no unload_start) and warm (one unload_start carried down the
!> overlaps in order, as a curve's solves carry theirs); "again": the warm solve repeated
!> at the same overlap from its own deflection. Per solve: the error relative to the
!> local force |P - P_ref|/max(P_ref, 1e-3 P(m)), |P - P_ref|/P(m), the solve's est_rel_err
!> and its CPU (cpu_time, one thread).
!>
!>   B=$(dirname $(find build -path '*/egw_hysteresis_lengths.mod' | head -1))
!>   gfortran -O2 -fopenmp -ffree-line-length-none -I$B tools/bench/front33_unload_scatter.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/front33_unload_scatter
!>   [EGW_PROBE_MODEL=GW] OMP_NUM_THREADS=1 /tmp/front33_unload_scatter 1e-4 1e-9 \
!>      "1e-5 1e-6 1e-7" 1.05 2 4 399.0373536808676s @128.04661242772806
!>
!> A turning point is m/delta_y, or in sigma with a trailing s; @D adds the overlap D
!> (sigma) to the turning point before it. Prints per overlap and tolerance a "sv" line
!> (m/delta_y, delta/sigma, u_ref, tol, hist, mode, err_local, err/P(m), est, CPU s) and
!> per turning point, tolerance and kind the worst and mean errors at u >= 1e-3 and the
!> mean CPU.
program front33_unload_scatter
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_params, only: contact_params, model_egw, model_gw, model_name
   use egw_rough_sphere, only: solver_options, solve_result, loading_history, load_history, &
      & solve_unload, unload_start
   use egw_hysteresis, only: hysteresis_table, build_hysteresis, hysteresis_eval, first_yield
   use egw_hysteresis_lengths, only: curve_options
   implicit none
   integer, parameter :: n_u = 12, max_d = 96, max_tol = 8, n_mode = 3, n_hist = 3
   real(dp), parameter :: u_targets(n_u) = [3.0e-2_dp, 2.0e-2_dp, 1.0e-2_dp, 7.0e-3_dp, &
      & 5.0e-3_dp, 3.0e-3_dp, 2.0e-3_dp, 1.5e-3_dp, 1.2e-3_dp, 1.0e-3_dp, 7.0e-4_dp, 5.0e-4_dp]
   character(len=5), parameter :: mode_name(n_mode) = ["cold ", "warm ", "again"]
   character(len=5), parameter :: hist_name(n_hist) = ["curve", "same ", "hist "]
   type(contact_params) :: p
   type(hysteresis_table) :: t
   type(egw_error), allocatable :: err
   type(loading_history) :: h_ref, h
   type(solve_result) :: peak, top, res
   type(unload_start) :: start, none
   type(solver_options) :: ref_opt, opt, curve_opt
   real(dp) :: tol, ref_tol, dy, m, lo, hi, f, k, state, c0, c1, scale
   real(dp) :: tols(max_tol), ds(max_d), p_ref(max_d), u_ref(max_d)
   real(dp) :: e_loc(max_d, n_mode), cpu(max_d, n_mode)
   integer :: n_tol, n_dd, i, j, it, stat, mode, hv, argi, n_arg, retries
   character(len=256) :: arg, which, label
   logical :: ok(max_d)

   call get_command_argument(1, arg)
   read (arg, *) tol
   call get_command_argument(2, arg)
   read (arg, *) ref_tol
   call get_command_argument(3, arg)
   n_tol = count_words(arg)
   read (arg, *) tols(1:n_tol)
   call get_environment_variable("EGW_PROBE_MODEL", which)
   if (len_trim(which) == 0) which = "E-GW"
   p = contact_params(model=model_egw, radius=405284.734569351_dp, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
   select case (trim(which))
   case ("E-GW")
   case ("GW")
      p%model = model_gw
   case default
      print '(a)', "EGW_PROBE_MODEL = "//trim(which)//": must be E-GW or GW"
      stop 1
   end select
   label = model_name(p%model)//" + cap"
   dy = first_yield(p)
   call build_hysteresis(p, solver_options(n_threads=1), 0.0_dp, 6*dy, tol, t, err)
   if (allocated(err)) then
      print '(a)', "build failed: "//err%message
      stop 1
   end if
   curve_opt = curve_options(solver_options(), tol)
   ref_opt = solver_options(rel_tol=ref_tol, n_threads=1)
   print '(a,es8.1,a,es23.16,a,i0,a,i0,a,es9.2,a,es9.2)', trim(label)//", table rel_tol", &
      & tol, ", delta_y ", dy, " sigma, grid ", size(t%m), " x ", size(t%s), &
      & ", curve solves at ", curve_opt%rel_tol, ", references at ", ref_tol
   print '(a)', "sv m/dy delta/sigma u_ref tol hist mode err_local err/P(m) est cpu_s"

   n_arg = command_argument_count()
   argi = 4
   do while (argi <= n_arg)
      call get_command_argument(argi, arg)
      argi = argi + 1
      if (arg(len_trim(arg):len_trim(arg)) == "s") then
         read (arg(1:len_trim(arg) - 1), *) m
      else
         read (arg, *) m
         m = m*dy
      end if
      ! the overlaps: where the table's force is u P(m) (bisection on the table), then @'s
      n_dd = 0
      do j = 1, n_u
         lo = -3.0_dp
         hi = m
         do it = 1, 60
            ds(n_dd + 1) = 0.5_dp*(lo + hi)
            state = m
            call hysteresis_eval(t, ds(n_dd + 1), state, f, k, stat)
            call hysteresis_eval(t, m, state, scale, k, stat)
            if (f > u_targets(j)*scale) then
               hi = ds(n_dd + 1)
            else
               lo = ds(n_dd + 1)
            end if
         end do
         n_dd = n_dd + 1
         ds(n_dd) = hi
      end do
      do while (argi <= n_arg)
         call get_command_argument(argi, arg)
         if (arg(1:1) /= "@") exit
         argi = argi + 1
         n_dd = n_dd + 1
         read (arg(2:), *) ds(n_dd)
      end do
      ! the references
      call load_history(p, ref_opt, m, h_ref, peak, err)
      if (allocated(err)) then
         print '(a,es23.16,a)', "reference history failed at m = ", m, ": "//trim(err%message)
         deallocate (err)
         cycle
      end if
      retries = 0
      do i = 1, n_dd
         ok(i) = .true.
         call cpu_time(c0)
         call solve_unload(h_ref, ds(i), res, err)
         if (allocated(err)) then
            deallocate (err)
            retries = retries + 1
            h_ref%options%rel_tol = 10*ref_tol
            call solve_unload(h_ref, ds(i), res, err)
            h_ref%options%rel_tol = ref_tol
            if (allocated(err)) then
               print '(a,2es23.16,a)', "reference failed at m, delta ", m, ds(i), ": " &
                  & //trim(err%message)
               deallocate (err)
               ok(i) = .false.
               cycle
            end if
         end if
         call cpu_time(c1)
         p_ref(i) = res%force
         u_ref(i) = res%force/peak%force
         print '(a,f12.8,es23.16,es12.4,a,es10.2,a,f8.3)', "ref m/dy ", m/dy, ds(i), u_ref(i), &
            & " est ", res%est_rel_err, " cpu ", c1 - c0
      end do
      print '(a,es23.16,a,es23.16,a,i0)', "turning point m = ", m, " sigma, P(m) ", &
         & peak%force, ", references retried at 10 REF: ", retries
      do j = 1, n_tol
         do hv = 1, n_hist
            opt = curve_opt
            if (hv >= 2) opt%rel_tol = tols(j)
            call cpu_time(c0)
            call load_history(p, opt, m, h, top, err, t%loading_law, stiffness=.false.)
            call cpu_time(c1)
            if (allocated(err)) then
               print '(a,es9.2,a)', "history failed at tol ", opt%rel_tol, ": " &
                  & //trim(err%message)
               deallocate (err)
               cycle
            end if
            print '(a,f12.8,es9.1,1x,a,a,f9.4,a,es10.2)', "history m/dy ", m/dy, tols(j), &
               & hist_name(hv), " cpu", c1 - c0, " P/P_ref(m) - 1", top%force/peak%force - 1
            h%options%rel_tol = tols(j)
            if (hv == 3) h%options%rel_tol = curve_opt%rel_tol
            e_loc = -1.0_dp
            cpu = 0.0_dp
            do mode = 1, n_mode
               if (mode == 2) start = none
               if (mode == 3) cycle   ! (done with mode 2)
               do i = 1, n_dd
                  if (.not. ok(i)) cycle
                  call one(mode, i)
                  if (mode == 2) call one(3, i)
               end do
            end do
            do mode = 1, n_mode
               call summary(j, hv, mode)
            end do
         end do
      end do
   end do

contains

   !> One unloading solve of h at overlap ds(i) (cold, or from start), printed and kept.
   subroutine one(mode, i)
      integer, intent(in) :: mode, i
      real(dp) :: e_abs
      call cpu_time(c0)
      if (mode == 1) then
         call solve_unload(h, ds(i), res, err)
      else
         call solve_unload(h, ds(i), res, err, start)
      end if
      call cpu_time(c1)
      if (allocated(err)) then
         print '(a,f12.8,es23.16,es9.2,a)', "sv-failed ", m/dy, ds(i), tols(j), ": " &
            & //trim(err%message)
         deallocate (err)
         return
      end if
      e_abs = abs(res%force - p_ref(i))/peak%force
      e_loc(i, mode) = abs(res%force - p_ref(i))/max(p_ref(i), 1.0e-3_dp*peak%force)
      cpu(i, mode) = c1 - c0
      print '(a,f12.8,es23.16,es11.3,es9.1,1x,a,1x,a,3es10.2,f9.4)', "sv ", m/dy, ds(i), &
         & u_ref(i), tols(j), hist_name(hv), mode_name(mode), e_loc(i, mode), e_abs, &
         & res%est_rel_err, c1 - c0
   end subroutine one

   !> Worst and mean error relative to the local force at u_ref >= 1e-3, the worst below
   !> it, and the mean CPU per solve, of one tolerance, history and kind.
   subroutine summary(j, hv, mode)
      integer, intent(in) :: j, hv, mode
      logical :: hi_u(max_d), lo_u(max_d)
      integer :: c
      hi_u(1:n_dd) = ok(1:n_dd) .and. e_loc(1:n_dd, mode) >= 0.0_dp .and. u_ref(1:n_dd) >= 1.0e-3_dp
      lo_u(1:n_dd) = ok(1:n_dd) .and. e_loc(1:n_dd, mode) >= 0.0_dp .and. u_ref(1:n_dd) < 1.0e-3_dp
      c = count(hi_u(1:n_dd))
      if (c == 0) return
      print '(a,f12.8,es9.1,1x,a,1x,a,a,i3,a,2es10.2,a,es10.2,a,f9.4)', "sum m/dy ", m/dy, &
         & tols(j), hist_name(hv), mode_name(mode), " u>=1e-3 n", c, " worst, mean", &
         & maxval(e_loc(1:n_dd, mode), hi_u(1:n_dd)), &
         & sum(e_loc(1:n_dd, mode), hi_u(1:n_dd))/c, " | u<1e-3 worst", &
         & maxval(e_loc(1:n_dd, mode), lo_u(1:n_dd)), " | cpu/solve", &
         & sum(cpu(1:n_dd, mode), ok(1:n_dd) .and. e_loc(1:n_dd, mode) >= 0.0_dp)/ &
         & max(1, count(ok(1:n_dd) .and. e_loc(1:n_dd, mode) >= 0.0_dp))
   end subroutine summary

   integer function count_words(s) result(c)
      character(len=*), intent(in) :: s
      integer :: q
      logical :: in_word
      c = 0
      in_word = .false.
      do q = 1, len_trim(s)
         if (s(q:q) /= " " .and. .not. in_word) c = c + 1
         in_word = s(q:q) /= " "
      end do
   end function count_words
end program front33_unload_scatter
