!> What the kink of rough + cap unloading curves near the knee is (doc/benchmarks.md
!> "Stop 67: kink33"; onset33 found it in the table's s, tools/bench/onset33_kink.py).
!> README's E-GW + cap (the table of rough_cap_local_decompose: R = 405284.734569351
!> effective, E* = sigma = 1, mu 4, p_y = 0.01, delta_y = 100 sigma). Per turning point m
!> (in delta_y), from a history at rel_tol 1e-9:
!>  - the plastic field it keeps (cap_fields on its closest approach, 8001 radii): b, the
!>    outer edge of the capped body (plastic gap shift > 0), c, the outer edge of the
!>    capped zone (pressure offset > 0: body + the edge band), and r_0 = sqrt(R (m -
!>    delta_y)), where the Hertz pressure at m is p_y;
!>  - delta_open: the largest overlap of the unloading where the total pressure (floored
!>    at 0) has a zero inside the contact followed by pressure farther out (a separated
!>    annulus; "Stop 56: kink22"): scanned down from m - delta_y + 6 sigma in 0.25 sigma
!>    steps, then bisected 20 times (unloading solves at 1e-8, at 1e-6 where that fails,
!>    8001 radii to 3 sqrt(R m): on 31 nodes from 1.0027 delta_y 20001 more on [0.7 c,
!>    1.2 c] moved it by at most 1.5e-5 sigma);
!>    r_k its first radius, a = sqrt(R delta_open) the Hertz radius there;
!>  - delta_stiff: the overlap of the largest second difference of the unloading
!>    stiffness on a 0.005 sigma grid, +-0.15 sigma about delta_open (solve_unload at 1e-8,
!>    at 1e-6 where that fails: counted);
!>    the force's kink, checked against the annulus;
!>  - x = m - delta_open, and x - delta_y.
!> Lengths in sigma. One thread.
!>
!>   B=$(dirname $(find build -path '*/egw_sphere_problem.mod' | head -1))
!>   gfortran -O2 -fopenmp -ffree-line-length-none -I$B tools/bench/kink33_annulus.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/kink33_annulus
!>   OMP_NUM_THREADS=1 /tmp/kink33_annulus 1.02075 1.03024 ...   # m in delta_y
program kink33_annulus
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_params, only: contact_params, model_egw, length_unit
   use egw_rough_sphere, only: solver_options, solve_result, loading_history, load_history, &
      & solve_unload, unloading_problem
   use egw_sphere_problem, only: scaled_problem, discrete_solution, cap_fields, closest_gap, &
      & total_pressure, negligible
   use egw_sphere_solver, only: solve_scaled
   use egw_hysteresis, only: first_yield
   implicit none
   integer, parameter :: n_r = 8001, n_s = 30
   type(contact_params) :: p
   type(egw_error), allocatable :: err
   type(loading_history) :: hist
   type(solve_result) :: peak, res
   type(scaled_problem) :: prob
   real(dp), allocatable :: rs(:), gmin(:), ps(:), dps(:), shift(:), offset(:)
   real(dp) :: dy, m, lu, b, c, r0, lo, hi, d, r_k, ks(-n_s:n_s), best, d_s, d2
   integer :: k, j, it, retried
   character(len=32) :: arg
   p = contact_params(model=model_egw, radius=405284.734569351_dp, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
   dy = first_yield(p)
   lu = length_unit(p)
   print '(a,f10.4,a)', "delta_y = ", dy, " sigma; lengths in sigma"
   print '(a)', "  m/delta_y         b         c       r_0   delta_open  delta_stiff" // &
      & "        r_k  a(delta_open)  x - delta_y"
   do k = 1, command_argument_count()
      call get_command_argument(k, arg)
      read (arg, *) m
      m = m*dy
      call load_history(p, solver_options(rel_tol=1.0e-9_dp, n_threads=1), m, hist, peak, err)
      if (allocated(err)) then
         print '(a,f10.5,a)', "history failed at ", m/dy, ": "//err%message
         deallocate (err)
         cycle
      end if
      ! the plastic field of the history: body (shift > 0) and zone (offset > 0) edges
      prob = unloading_problem(hist, 0.5_dp*m)
      rs = [(3.0_dp*sqrt(m/p%sigma)*j/(n_r - 1), j = 0, n_r - 1)]
      gmin = closest_gap(prob%closest, rs)
      call cap_fields(prob, rs, gmin, ps, dps, shift, offset)
      b = 0.0_dp
      c = 0.0_dp
      do j = 1, n_r
         if (shift(j) > 0.0_dp) b = rs(j)*lu
         if (offset(j) > 0.0_dp) c = rs(j)*lu
      end do
      r0 = sqrt(p%radius*max(m - dy, 0.0_dp))
      ! the annulus: scan down, then bisect
      hi = m - dy + 6.0_dp
      do while (opened(hi, r_k) .and. hi < m)   ! (open already: start higher)
         hi = hi + 5.0_dp
      end do
      lo = hi
      do while (.not. opened(lo, r_k))
         hi = lo
         lo = lo - 0.25_dp
         if (lo < -2.0_dp) exit
      end do
      if (lo < -2.0_dp) then
         print '(f11.5,3f10.1,a)', m/dy, b, c, r0, "   no annulus above -2 sigma"
         flush (6)
         cycle
      end if
      do it = 1, 20
         d = 0.5_dp*(lo + hi)
         if (opened(d, r_k)) then
            lo = d
         else
            hi = d
         end if
      end do
      if (.not. opened(lo, r_k)) error stop "annulus lost"
      ! the force's kink: the stiffness's largest second difference
      hist%options%rel_tol = 1.0e-8_dp
      retried = 0
      do j = -n_s, n_s
         call solve_unload(hist, lo + 0.005_dp*j, res, err)
         if (allocated(err)) then   ! (at 1e-6 where 1e-8 fails)
            deallocate (err)
            hist%options%rel_tol = 1.0e-6_dp
            call solve_unload(hist, lo + 0.005_dp*j, res, err)
            hist%options%rel_tol = 1.0e-8_dp
            if (allocated(err)) then
               print '(a,f10.5,a,f10.4,a)', "  (m ", m/dy, ", delta ", lo + 0.005_dp*j, &
                  & ": "//err%message//")"
               deallocate (err)
               res%stiffness = 0.0_dp
            end if
            retried = retried + 1
         end if
         ks(j) = res%stiffness
      end do
      best = 0.0_dp
      d_s = lo
      do j = -n_s + 1, n_s - 1
         d2 = abs(ks(j + 1) - 2.0_dp*ks(j) + ks(j - 1))
         if (d2 > best) then
            best = d2
            d_s = lo + 0.005_dp*j
         end if
      end do
      print '(f11.5,3f10.1,2f13.4,f11.1,f15.1,f13.4,a,i0)', m/dy, b, c, r0, lo, d_s, r_k, &
         & sqrt(p%radius*max(lo, 0.0_dp)), m - lo - dy, "  retried ", retried
      flush (6)
   end do
contains
   !> Whether the floored total unloading pressure at overlap d has a zero inside the
   !> contact (followed farther out by positive pressure); rk its first radius (sigma).
   logical function opened(d, rk)
      real(dp), intent(in) :: d
      real(dp), intent(out) :: rk
      type(scaled_problem) :: q
      type(discrete_solution) :: sol
      real(dp) :: est, pr(n_r), rr(n_r)
      integer :: i, method
      opened = .false.
      rk = 0.0_dp
      q = unloading_problem(hist, d)
      if (negligible(q)) return
      call solve_scaled(q, solver_options(rel_tol=1.0e-8_dp, n_threads=1), sol, est, method, &
         & err)
      if (allocated(err)) then   ! (1e-8 can miss near the front: at 1e-6 then)
         deallocate (err)
         call solve_scaled(q, solver_options(rel_tol=1.0e-6_dp, n_threads=1), sol, est, &
            & method, err)
         if (allocated(err)) then
            print '(a,f10.5,a,f10.4,a)', "  (m ", m/dy, ", delta ", d, ": "//err%message//")"
            deallocate (err)
            return
         end if
      end if
      rr = [(3.0_dp*sqrt(m/p%sigma)*i/(n_r - 1), i = 0, n_r - 1)]
      do i = 1, n_r
         pr(i) = total_pressure(q, sol, rr(i))
      end do
      call interior_zero(rr, pr, opened, rk)
   end function opened

   !> Whether the pressures pr (floored total) at increasing scaled radii r have a zero
   !> followed by a positive pressure farther out; rk the zero's first radius (sigma).
   subroutine interior_zero(r, pr, found, rk)
      real(dp), intent(in) :: r(:), pr(:)
      logical, intent(out) :: found
      real(dp), intent(out) :: rk
      real(dp) :: top
      integer :: i, i0
      found = .false.
      rk = 0.0_dp
      top = maxval(pr)
      do i0 = 2, size(pr)
         if (pr(i0) <= 1.0e-14_dp*top) exit
      end do
      do i = i0, size(pr)
         if (pr(i) > 1.0e-14_dp*top) then
            found = .true.
            rk = r(i0)*lu
            return
         end if
      end do
   end subroutine interior_zero
end program kink33_annulus
