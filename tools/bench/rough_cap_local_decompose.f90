!> Where a rough + cap hysteresis table's error relative to the local force comes from
!> (issue 33 item 5; doc/benchmarks.md "Stop 58: local24"). README's E-GW + cap table
!> (egw-table --radius 810569.469138702 --effective-modulus 1 --sigma 1 --mu 4
!> --flow-pressure 0.01 --delta-max 600 --tol TOL: R = 405284.734569351 effective,
!> delta_y = 100 sigma, to 6 delta_y), or with EGW_PROBE_MODEL = EP-GW, psi1 or GW
!> (default E-GW) the same scene's EP-GW + cap (--model EP-GW), EP-GW psi 1 + cap
!> (--model EP-GW --psi 1) or GW + cap (--model GW) table, the contact_params egw-table
!> builds for them (its other parameters the defaults, as egw-table's), is built; at
!> turning points m (the
!> midpoints of its delta_max intervals and its nodes, from 1.01 delta_y) and n_d
!> overlaps from m down to where the table's force is 1e-3 P(m) (graded toward that end),
!> three forces: P_ref, a history and unloading solve at REF (independent of the table);
!> P_b, the curve solve the build would make there (its history at the build's curve
!> tolerance, its ZMC law table, loaded without the stiffness, the unloading solve at that
!> tolerance); P_t, the table's. Errors relative to max(P_ref, 1e-3 P_ref(m)):
!>   hist = |P_b - P_ref| (the histories' own error),
!>   tab  = |P_t - P_b| (the table against its own solves: at the nodes the s
!>          interpolation alone, at the midpoints the s and the delta_max interpolation),
!>   tot  = |P_t - P_ref|,
!> worst and median per P_ref/P(m) band, midpoints and nodes apart. A reference solve that
!> fails is retried at 10 REF (counted). One thread.
!>
!>   B=$(dirname $(find build -path '*/egw_hysteresis_lengths.mod' | head -1))
!>   gfortran -O2 -fopenmp -ffree-line-length-none -I$B tools/bench/rough_cap_local_decompose.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/rough_cap_local_decompose
!>   [EGW_PROBE_MODEL=EP-GW|psi1|GW] OMP_NUM_THREADS=1 /tmp/rough_cap_local_decompose \
!>      1e-4 12 1e-8 [STRIDE] [REPLAY]
!>
!> EGW_PROBE_HIST_SHARE (default 1): P_b's history at that fraction of the curve solves'
!> rel_tol (0.1 for w34's builds, 0.01 for gw34's rough + cap u curves), its unloading
!> solves at theirs.
!> STRIDE (default 1): every STRIDE-th interval and node; n_d = 0: the build alone. Prints
!> per overlap a "pt" line (kind, m/delta_y, delta/delta_y, P_ref/P(m), hist, tab, tot) and
!> a "ref" line (kind, is node, m, delta, P_ref, P_b, P(m) in full), then the band
!> summaries. REPLAY, a file of such output: this build's table at those "ref" points
!> instead of new solves (another build's table against the same references, in seconds).
program rough_cap_local_decompose
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_params, only: contact_params, model_egw, model_epgw, model_gw, model_name
   use egw_rough_sphere, only: solver_options, solve_result, loading_history, load_history, &
      & solve_unload
   use egw_hysteresis, only: hysteresis_table, build_hysteresis, hysteresis_eval, first_yield
   use egw_hysteresis_lengths, only: curve_options
   implicit none
   integer, parameter :: n_band = 4, max_pts = 20000
   real(dp), parameter :: band_lo(n_band) = [0.1_dp, 0.01_dp, 0.003_dp, 0.0_dp]
   type(contact_params) :: p
   type(hysteresis_table) :: t
   type(egw_error), allocatable :: err
   type(loading_history) :: h_ref, h_b
   type(solve_result) :: peak, peak_b, res
   type(solver_options) :: ref_opt, build_opt, hist_opt, defaults
   real(dp) :: tol, ref_tol, dy, m, d, d_end, lo, hi, f, k, state, p_ref, p_b, p_t, scale, &
      & cpu0, cpu1, hist_share
   real(dp), allocatable :: ms(:)
   logical, allocatable :: is_node(:)
   real(dp) :: e(3, max_pts), frac(max_pts)
   logical :: node_pt(max_pts)
   integer :: n_d, stride, j, i, it, stat, n, n_m, retries
   character(len=64) :: arg, which, label
   call get_command_argument(1, arg)
   read (arg, *) tol
   call get_command_argument(2, arg)
   read (arg, *) n_d
   call get_command_argument(3, arg)
   read (arg, *) ref_tol
   stride = 1
   if (command_argument_count() >= 4) then
      call get_command_argument(4, arg)
      read (arg, *) stride
   end if
   call get_environment_variable("EGW_PROBE_MODEL", which)
   if (len_trim(which) == 0) which = "E-GW"
   p = contact_params(model=model_egw, radius=405284.734569351_dp, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
   select case (trim(which))
   case ("E-GW")
   case ("EP-GW")
      p%model = model_epgw
   case ("psi1")
      p%model = model_epgw
      p%psi = 1.0_dp
   case ("GW")
      p%model = model_gw
   case default
      print '(a)', "EGW_PROBE_MODEL = "//trim(which)//": must be E-GW, EP-GW, psi1 or GW"
      stop 1
   end select
   label = model_name(p%model)//" + cap"
   if (p%psi > 0.0_dp) label = model_name(p%model)//" psi 1 + cap"
   dy = first_yield(p)
   call cpu_time(cpu0)
   call build_hysteresis(p, solver_options(n_threads=1), 0.0_dp, 6*dy, tol, t, err)
   call cpu_time(cpu1)
   if (allocated(err)) then
      print '(a)', "build failed: "//err%message
      stop 1
   end if
   print '(a,es8.1,a,f8.3,a,f8.2,a,i0,a,i0,a,es10.3)', trim(label)//", rel_tol", tol, &
      & ", delta_y", dy, " sigma: build CPU", cpu1 - cpu0, " s, n_m ", size(t%m), ", n_s ", &
      & size(t%s), ", max_error ", t%max_error
   if (n_d == 0) stop   ! (the build alone: its CPU)
   if (command_argument_count() >= 5) then
      call get_command_argument(5, arg)
      call replay(trim(arg))
      stop
   end if
   ref_opt = solver_options(rel_tol=ref_tol, n_threads=1)
   build_opt = curve_options(solver_options(), tol)
   hist_share = 1.0_dp
   call get_environment_variable("EGW_PROBE_HIST_SHARE", arg, status=stat)
   if (stat == 0 .and. len_trim(arg) > 0) read (arg, *) hist_share
   print '(a,es9.2,a,es9.2)', "curve solves at rel_tol", build_opt%rel_tol, &
      & ", references at", ref_tol
   ! the turning points: every stride-th interval's midpoint and node above 1.01 delta_y
   n_m = 0
   allocate (ms(2*size(t%m)), is_node(2*size(t%m)))
   do j = 1, size(t%m) - 1, stride
      m = 0.5_dp*(t%m(j) + t%m(j + 1))
      if (m > 1.01_dp*dy) then
         n_m = n_m + 1
         ms(n_m) = m
         is_node(n_m) = .false.
      end if
      if (t%m(j + 1) > 1.01_dp*dy) then
         n_m = n_m + 1
         ms(n_m) = t%m(j + 1)
         is_node(n_m) = .true.
      end if
   end do
   n = 0
   retries = 0
   do j = 1, n_m
      m = ms(j)
      call load_history(p, ref_opt, m, h_ref, peak, err)
      if (allocated(err)) then
         print '(a,f9.3,a)', "reference history failed at m = ", m, ": "//trim(err%message)
         deallocate (err)
         cycle
      end if
      ! (the build's history: at hist_share of the curve solves' rel_tol, then theirs)
      hist_opt = build_opt
      hist_opt%rel_tol = hist_share*build_opt%rel_tol
      call load_history(p, hist_opt, m, h_b, peak_b, err, t%loading_law, stiffness=.false.)
      if (allocated(err)) stop 2
      h_b%options%rel_tol = build_opt%rel_tol
      ! where the table's force falls to 1e-3 P(m) (bisection on the table)
      lo = -3.0_dp
      hi = m
      do it = 1, 50
         d_end = 0.5_dp*(lo + hi)
         state = m
         call hysteresis_eval(t, d_end, state, f, k, stat)
         if (f > 1.0e-3_dp*peak%force) then
            hi = d_end
         else
            lo = d_end
         end if
      end do
      d_end = hi
      do i = 1, n_d
         d = m - (m - d_end)*(1.0_dp - (1.0_dp - i/real(n_d, dp))**2)
         call solve_unload(h_ref, d, res, err)
         if (allocated(err)) then
            ! (a 1e-8 solve near the front can miss its tolerance: kink22)
            deallocate (err)
            retries = retries + 1
            h_ref%options%rel_tol = 10*ref_tol
            call solve_unload(h_ref, d, res, err)
            h_ref%options%rel_tol = ref_tol
            if (allocated(err)) then
               print '(a,2f10.3)', "reference failed at m, delta ", m, d
               deallocate (err)
               cycle
            end if
         end if
         p_ref = res%force
         call solve_unload(h_b, d, res, err)
         if (allocated(err)) stop 3
         p_b = res%force
         state = m
         call hysteresis_eval(t, d, state, p_t, k, stat)
         scale = max(p_ref, 1.0e-3_dp*peak%force)
         n = n + 1
         e(:, n) = [abs(p_b - p_ref), abs(p_t - p_b), abs(p_t - p_ref)]/scale
         frac(n) = p_ref/peak%force
         node_pt(n) = is_node(j)
         print '(a,a,f9.5,f10.6,es10.2,3es10.2)', "pt ", merge("node", "mid ", is_node(j)), &
            & m/dy, d/dy, frac(n), e(:, n)
         print '(a,a,l2,5es25.16e3)', "ref ", merge("node", "mid ", is_node(j)), is_node(j), &
            & m, d, p_ref, p_b, peak%force
      end do
   end do
   print '(a,i0,a,i0,a,i0)', "overlaps ", n, ", turning points ", n_m, &
      & ", references retried at 10 REF ", retries
   call summary("midpoints", .false.)
   call summary("nodes", .true.)
contains
   !> The table against the forces of a previous run's "ref" lines (the same turning
   !> points and overlaps, P_ref and P_b as solved then): this build's tab and tot.
   subroutine replay(path)
      character(len=*), intent(in) :: path
      character(len=512) :: line
      character(len=4) :: tag, kind
      logical :: nd
      real(dp) :: v(5)
      integer :: u, ios
      open (newunit=u, file=path, status="old", action="read")
      n = 0
      do
         read (u, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (line(1:4) /= "ref ") cycle
         read (line, *) tag, kind, nd, v
         state = v(1)
         call hysteresis_eval(t, v(2), state, p_t, k, stat)
         n = n + 1
         scale = max(v(3), 1.0e-3_dp*v(5))
         e(:, n) = [abs(v(4) - v(3)), abs(p_t - v(4)), abs(p_t - v(3))]/scale
         frac(n) = v(3)/v(5)
         node_pt(n) = nd
         print '(a,a,f9.5,f10.6,es10.2,3es10.2)', "pt ", kind, v(1)/dy, v(2)/dy, frac(n), &
            & e(:, n)
      end do
      close (u)
      print '(a,i0,a)', "replayed ", n, " overlaps of "//path
      call summary("the run's midpoints", .false.)
      call summary("the run's nodes", .true.)
   end subroutine replay

   subroutine summary(label, nodes)
      character(len=*), intent(in) :: label
      logical, intent(in) :: nodes
      integer :: b, q, c
      real(dp) :: hi_b
      logical :: sel(max_pts)
      print '(a)', label//": band P_ref/P(m) | n | worst hist, tab, tot | median hist, tab, tot"
      do b = 1, n_band
         hi_b = 1.0_dp + 1.0e-9_dp
         if (b > 1) hi_b = band_lo(b - 1)
         sel(1:n) = node_pt(1:n) .eqv. nodes
         sel(1:n) = sel(1:n) .and. frac(1:n) >= band_lo(b) .and. frac(1:n) < hi_b
         c = count(sel(1:n))
         if (c == 0) cycle
         print '(a,f6.3,a,f6.3,a,i5,a,3es9.2,a,3es9.2)', "  [", band_lo(b), ",", hi_b, ")", c, &
            & " |", (maxval(e(q, 1:n), mask=sel(1:n)), q = 1, 3), " |", &
            & (median(pack(e(q, 1:n), sel(1:n))), q = 1, 3)
      end do
   end subroutine summary

   real(dp) function median(x) result(v)
      real(dp), intent(in) :: x(:)
      real(dp) :: y(size(x)), tmp
      integer :: a, b
      y = x
      do a = 2, size(y)   ! (insertion sort: a few hundred values)
         tmp = y(a)
         b = a - 1
         do while (b >= 1)
            if (y(b) <= tmp) exit
            y(b + 1) = y(b)
            b = b - 1
         end do
         y(b + 1) = tmp
      end do
      v = y((size(y) + 1)/2)
   end function median
end program rough_cap_local_decompose
