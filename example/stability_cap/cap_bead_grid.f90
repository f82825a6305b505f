!> Stability of the rough solver with the flow-pressure cap on real bead pairs (issue 32,
!> doc/stability.md "Rough spheres with the cap"): egw `restitution` for glass and steel
!> pairs (doc/restitution.md's, R* = 0.5 mm, m* = m/2), E-GW + cap and EP-GW + cap at four
!> pair roughnesses sigma from 10 nm to 1 um (and Hertz + cap), six speeds from 1 mm/s to
!> 10 m/s, at rel_tol 1e-4 and the default 1e-6. Records each impact's status, e,
!> delta_max/delta_y and time in out/cap_bead_grid.csv (written atomically) and prints
!> the failures and the slowest impacts. It asserts nothing about convergence (the map is
!> the measurement); exit status 1 only if a success has e outside (0, 1] or a failure is
!> not egw_not_converged (the inputs are valid).
!>
!> Usage: fpm run --profile release --example cap-bead-grid [-- 1e-4 [1e-6 ...]]
!> (impacts in parallel with OpenMP, one thread per solve; ~1 min at 1e-4 on 2 cores, the
!> 1e-6 grid several minutes: some fast steel impacts refine to the finest mesh).
program cap_bead_grid
   use egw, only: dp, contact_params, model_hertz, model_egw, model_epgw, solver_options, &
      & egw_error, egw_not_converged, restitution, first_yield_overlap, &
      & open_temporary, commit_temporary, discard_temporary
   use, intrinsic :: iso_fortran_env, only: int64
   implicit none
   character(len=*), parameter :: path = "out/cap_bead_grid.csv"
   real(dp), parameter :: pi = acos(-1.0_dp)
   integer, parameter :: n_v = 6, n_sigma = 4
   real(dp), parameter :: speeds(n_v) = [1.0e-3_dp, 1.0e-2_dp, 0.1_dp, 1.0_dp, 3.0_dp, &
      & 10.0_dp]
   real(dp), parameter :: sigmas(n_sigma) = [1.0e-8_dp, 4.2e-8_dp, 1.77e-7_dp, 1.0e-6_dp]
   character(len=5), parameter :: materials(2) = ["glass", "steel"]
   !> doc/restitution.md's pairs: E, nu, density, p_y = 1.6 Y, psi (K = 0.6), mu 4
   real(dp), parameter :: e_young(2) = [70.0e9_dp, 210.0e9_dp], nu(2) = [0.22_dp, 0.30_dp], &
      & density(2) = [2500.0_dp, 7830.0_dp], p_y(2) = [3.14e9_dp, 3.2e9_dp], &
      & psis(2) = [0.31_dp, 1.02_dp]
   real(dp), parameter :: bead = 1.0e-3_dp   ! bead radius [m]
   type :: impact
      integer :: material = 1, model = model_egw, stat = 0
      real(dp) :: sigma = 0.0_dp, v = 0.0_dp, tol = 1.0e-4_dp, e = 0.0_dp, depth = 0.0_dp
      real(dp) :: seconds = 0.0_dp
   end type impact
   type(impact), allocatable :: runs(:)
   real(dp), allocatable :: tols(:)
   character(len=:), allocatable :: tmp_path
   type(egw_error), allocatable :: error
   character(len=32) :: arg
   integer :: n, i, k, unit, ios, n_fail, n_bad, order(5)
   real(dp) :: t_sum

   n = command_argument_count()
   if (n == 0) then
      tols = [1.0e-4_dp, 1.0e-6_dp]
   else
      allocate (tols(n))
      do i = 1, n
         call get_command_argument(i, arg)
         read (arg, *, iostat=ios) tols(i)
         if (ios /= 0 .or. .not. (tols(i) >= 1.0e-8_dp .and. tols(i) <= 1.0e-2_dp)) &
            & call fail("rel_tol '"//trim(arg)//"': a number in [1e-8, 1e-2]")
      end do
   end if
   call make_runs()
   !$omp parallel do schedule(dynamic, 1) num_threads(2)
   do i = 1, size(runs)
      call run_one(runs(i))
   end do
   !$omp end parallel do

   call execute_command_line("mkdir -p out")
   call open_temporary(path, unit, tmp_path, error)
   if (allocated(error)) call fail(error%message)
   write (unit, '(a)', iostat=ios) "# egw restitution of glass and steel bead pairs with the "// &
      & "flow-pressure cap (example/stability_cap); stat 0 = converged"
   write (unit, '(a)', iostat=ios) "material,model,sigma,velocity,rel_tol,stat,e,"// &
      & "delta_max_over_delta_y,seconds"
   if (ios /= 0) call fail("cannot write "//path)
   n_fail = 0
   n_bad = 0
   do i = 1, size(runs)
      associate (r => runs(i))
         write (unit, '(a,",",i0,",",es10.3,",",es10.3,",",es8.1,",",i0,",",es16.9,",",' &
            & //'es12.5,",",f9.2)', iostat=ios) materials(r%material), r%model, r%sigma, &
            & r%v, r%tol, r%stat, r%e, r%depth, r%seconds
         if (ios /= 0) call fail("cannot write "//path)
         if (r%stat /= 0) then
            n_fail = n_fail + 1
            write (*, '(a,a,a,i0,a,es8.1,a,es8.1,a,es8.1,a,i0)') "  not converged: ", &
               & materials(r%material), " model ", r%model, " sigma ", r%sigma, " v ", r%v, &
               & " rel_tol ", r%tol, " stat ", r%stat
            if (r%stat /= egw_not_converged) n_bad = n_bad + 1
         else if (.not. (r%e > 0.0_dp .and. r%e <= 1.0_dp)) then
            n_bad = n_bad + 1
            write (*, '(a,es12.5)') "  check failed: e outside (0, 1]: ", r%e
         end if
      end associate
   end do
   call commit_temporary(unit, tmp_path, path, error)
   if (allocated(error)) call fail(error%message)
   do k = 1, size(tols)
      t_sum = sum(runs%seconds, mask=runs%tol == tols(k))
      write (*, '(a,es8.1,a,i0,a,i0,a,f8.1,a)') "rel_tol ", tols(k), ": ", &
         & count(runs%tol == tols(k) .and. runs%stat /= 0), " of ", &
         & count(runs%tol == tols(k)), " impacts not converged, ", t_sum, " s in all (one thread each)"
   end do
   order = slowest(5)
   write (*, '(a)') "slowest impacts:"
   do k = 1, size(order)
      associate (r => runs(order(k)))
         write (*, '(2x,a,a,i0,a,es8.1,a,es8.1,a,es8.1,a,f8.1,a,i0)') materials(r%material), &
            & " model ", r%model, " sigma ", r%sigma, " v ", r%v, " rel_tol ", r%tol, ": ", &
            & r%seconds, " s, stat ", r%stat
      end associate
   end do
   write (*, '(a)') "wrote "//path
   if (n_bad > 0) error stop 1

contains

   !> The grid: per tolerance, material and speed: Hertz + cap, then E-GW + cap and
   !> EP-GW + cap at each sigma.
   subroutine make_runs()
      integer :: it, m, iv, is, model, j
      allocate (runs(size(tols)*2*n_v*(1 + 2*n_sigma)))
      j = 0
      do it = 1, size(tols)
         do m = 1, 2
            do iv = 1, n_v
               do is = 0, n_sigma
                  do model = model_egw, model_epgw
                     if (is == 0 .and. model == model_epgw) cycle
                     j = j + 1
                     runs(j)%material = m
                     runs(j)%v = speeds(iv)
                     runs(j)%tol = tols(it)
                     if (is == 0) then
                        runs(j)%model = model_hertz
                     else
                        runs(j)%model = model
                        runs(j)%sigma = sigmas(is)
                     end if
                  end do
               end do
            end do
         end do
      end do
   end subroutine make_runs

   subroutine run_one(r)
      type(impact), intent(inout) :: r
      type(contact_params) :: p
      type(solver_options) :: opts
      type(egw_error), allocatable :: err
      real(dp) :: modulus, mass, dissipated, depth
      integer(int64) :: c0, c1, rate
      modulus = e_young(r%material)/(2.0_dp*(1.0_dp - nu(r%material)**2))
      mass = 0.5_dp*density(r%material)*4.0_dp*pi*bead**3/3.0_dp
      p = contact_params(model=r%model, radius=0.5_dp*bead, modulus=modulus, &
         & sigma=r%sigma, mu=4.0_dp, psi=0.0_dp, flow_pressure=p_y(r%material))
      if (r%model == model_epgw) p%psi = psis(r%material)
      if (r%model == model_hertz) p%mu = 1.0_dp
      opts%rel_tol = r%tol
      opts%n_threads = 1
      call system_clock(c0, rate)
      call restitution(p, opts, mass, r%v, r%e, dissipated, err, max_overlap=depth)
      call system_clock(c1)
      r%seconds = real(c1 - c0, dp)/real(rate, dp)   ! wall: one thread per impact
      r%stat = 0
      if (allocated(err)) then
         r%stat = err%stat
         r%e = 0.0_dp
         return
      end if
      r%depth = depth/first_yield_overlap(p)
   end subroutine run_one

   !> Indices of the n slowest impacts, slowest first.
   function slowest(n) result(idx)
      integer, intent(in) :: n
      integer :: idx(n), k
      logical :: taken(size(runs))
      taken = .false.
      do k = 1, n
         idx(k) = maxloc(runs%seconds, mask=.not. taken, dim=1)
         taken(idx(k)) = .true.
      end do
   end function slowest

   subroutine fail(message)
      character(len=*), intent(in) :: message
      write (*, '(a)') "cap-bead-grid: "//message
      if (allocated(tmp_path)) call discard_temporary(unit, tmp_path)
      error stop 1
   end subroutine fail

end program cap_bead_grid
