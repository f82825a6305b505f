!> egw's periodic FFT boundary-element solver of a rough flat: the frictionless,
!> non-adhesive, hard-wall contact of a periodic height map with a flat, load- or
!> gap-controlled, and the flat law p(u) with its area and stiffness built from it.
!>
!> **Problem.** A periodic rough surface, heights h(i, j) on nx x ny square pixels of size
!> `pixel` (periods Lx = nx pixel, Ly = ny pixel), is pressed against a flat; one of the
!> two is an elastic half-space of effective modulus E* (`modulus`; 1/E* = (1 - nu1^2)/E1
!> + (1 - nu2^2)/E2), the other rigid. The pressure is one value per pixel (the mean over
!> the pixel); the surface displacement w (positive: away from the flat) answers it in
!> Fourier space by the half-space's stiffness E*|q|/2 at the map's wave vectors
!> q = 2 pi (kx/Lx, ky/Ly), kx, ky the integer frequencies of the discrete transform (as
!> ContactMechanics' PeriodicFFTElasticHalfSpace). The q = 0 mode of w is the rigid-body
!> mode: w has zero mean, and the mean pressure is held by the constraint below.
!>
!> **Conventions.** Heights are measured from their mean plane (the mean is removed).
!> The gap is g = u - h + w >= 0, p >= 0, p g = 0 on every pixel, where u is the
!> position of the flat above the mean plane; as w has zero mean, u is the mean of the
!> gap field over all pixels: the **mean separation**, measured from the mean plane of
!> the heights. p-bar = the mean pressure over the nominal area nx ny pixel^2 (units of
!> `modulus`); the **area fraction** is the number of pixels with p > 0 over nx ny. A
!> periodic surface is in full contact (area fraction 1) at u = 0 under every load at or
!> above its full-contact load: then u stays 0 and the stiffness is infinite.
!>
!> **Method.** Constrained conjugate gradients of I. A. Polonsky & L. M. Keer, Wear 231
!> (1999) 206-219 (their steps 1-11): CG on the pixels in contact, projection onto
!> p >= 0, pixels that penetrate while carrying no pressure added with a restart of the
!> CG directions; load control removes the mean of the gap residual over the contact
!> set (the rigid approach) and rescales p to the mean pressure each step, gap control
!> keeps u fixed. Two FFT convolutions (FFTW3, r2c/c2r) per step. A solve is
!> warm-started from the pressure field the `bem_state` holds (the previous solve), else
!> from a uniform pressure (load control) or a Jacobi guess from the penetration (gap
!> control).
!>
!> **Convergence.** A solve has converged when the largest |g| over the contact set
!> and the largest penetration -g off it are both <= `tolerance` x (rms height of the
!> map), with p >= 0 exactly and (load control) mean(p) = p-bar to round-off. After
!> `max_iter` steps without that: egw_not_converged, with the residual reached.
!>
!> **Stiffness.** -dp-bar/du of the discrete problem with its contact set held: the
!> pressure x on the contact set that gives a uniform unit displacement there
!> ((G x)_i = 1, G the pressure-to-displacement operator restricted to the contact set;
!> plain CG), k = mean(x). For frictionless contact the contact set's change adds
!> nothing at first order (as dF/d delta = 2 a E* for Hertz), so this is the slope of
!> the curve; test/test_flat_bem.f90 checks it against the curve's finite differences.
!>
!> **Global state.** FFTW's planner is not thread-safe: plans are made and destroyed
!> inside the named critical section `egw_fftw_planner`, where fftw_init_threads is also
!> called once per process (the module's only saved variable, `fftw_threads_ready`).
!> Plans use FFTW_ESTIMATE (no measurement, no wisdom), so results are reproducible for a
!> given thread count. Everything else travels in arguments and the `bem_state`.
!>
!> **Threads.** `options%n_threads` threads run FFTW and the pointwise loops: about twenty
!> short parallel regions per CG step, so on an oversubscribed machine (more runnable
!> threads than cores) one thread can be much faster than two (egw-bench --bem, 512^2:
!> 10 s on 2 threads when quiet, 22 s on 1 thread and 160 s on 2 at load average 5).
!> A map gets at most one thread per 128^2 pixels: an 8 x 8 map on two threads beside
!> another busy process took 15 s instead of 0.1 s (egw-fuzz), every barrier a time slice.
module egw_flat_bem
   use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_associated, c_loc, c_int
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   !$ use omp_lib, only: omp_get_max_threads
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error, egw_invalid_argument, egw_not_converged, &
      & egw_out_of_memory, fatal_error, parameter_error, format_real, int_str
   use egw_fftw, only: fftw_plan_dft_r2c_2d, fftw_plan_dft_c2r_2d, fftw_execute, &
      & fftw_destroy_plan, fftw_init_threads, fftw_plan_with_nthreads, fftw_estimate_flag, &
      & fftw_destroy_input_flag
   implicit none
   private

   public :: bem_solve_load, bem_solve_gap, bem_flat_curve, bem_state_release

   !> Options of a solve. Defaults: tolerance 1e-10 of the rms height, 20000 steps,
   !> OpenMP's default thread count, no fields kept, no stiffness.
   type, public :: bem_options
      !> converged when the gap residual (contact set) and the penetration (elsewhere)
      !> are at most tolerance x rms height
      real(dp) :: tolerance = 1.0e-10_dp
      integer :: max_iter = 20000      !< CG steps per solve (each: two FFT convolutions)
      integer :: n_threads = 0         !< OpenMP and FFTW threads; 0: omp_get_max_threads()
      logical :: keep_fields = .false. !< fill result%pressure and result%gap
      logical :: stiffness = .false.   !< compute result%stiffness (one linear CG solve)
      !> relative residual of the stiffness solve ((G x)_i = 1 on the contact set)
      real(dp) :: stiffness_tolerance = 1.0e-10_dp
   end type bem_options

   !> What a solve leaves for the next one: the FFT plans and buffers of the grid, the
   !> Fourier compliance, and the last converged pressure field (the warm start). Reuse
   !> one state for a sequence of solves on the same grid; a copied state makes its own
   !> plans on first use.
   type, public :: bem_state
      private
      integer :: nx = 0, ny = 0, threads = 0
      real(dp) :: pixel = 0.0_dp, modulus = 0.0_dp
      real(dp) :: self_compliance = 0.0_dp   ! displacement of a pixel under its own unit pressure
      real(dp), allocatable :: pressure(:, :)  ! last converged pressure (warm start)
      real(dp), allocatable :: response(:, :)  ! last stiffness solution (warm start)
      real(dp), allocatable :: compliance(:, :)  ! 2/(E*|q|)/(nx ny) on the r2c half-spectrum
      real(dp), allocatable :: real_buffer(:, :)
      complex(dp), allocatable :: spectrum(:, :)
      type(c_ptr) :: forward = c_null_ptr, backward = c_null_ptr
      type(c_ptr) :: planned_buffer = c_null_ptr  ! real_buffer's address when planned
   end type bem_state

   !> Result of one solve.
   type, public :: bem_result
      real(dp) :: mean_separation = 0.0_dp  !< u: mean gap, from the heights' mean plane
      real(dp) :: mean_pressure = 0.0_dp    !< p-bar: mean pressure over the nominal area
      real(dp) :: area_fraction = 0.0_dp    !< pixels with p > 0 over nx ny
      !> -dp-bar/du, units of modulus/length (options%stiffness); huge() in full contact
      real(dp) :: stiffness = 0.0_dp
      integer :: iterations = 0             !< CG steps taken
      real(dp), allocatable :: pressure(:, :)  !< pressure field (options%keep_fields)
      real(dp), allocatable :: gap(:, :)       !< gap field (options%keep_fields)
   end type bem_result

   integer, parameter :: pixels_per_thread = 128*128
   logical, save :: fftw_threads_ready = .false.  ! guarded by critical(egw_fftw_planner)

contains

   !> One load-controlled solve: the contact of the map under the mean pressure
   !> `mean_pressure`, warm-started from `state`'s last pressure field if it has one of
   !> this grid.
   subroutine bem_solve_load(heights, pixel, modulus, mean_pressure, options, state, result, &
      & error)
      real(dp), intent(in) :: heights(:, :)    !< h(i, j), any length unit; periodic
      real(dp), intent(in) :: pixel            !< pixel size (> 0, same unit as heights)
      real(dp), intent(in) :: modulus          !< effective modulus E* (> 0)
      real(dp), intent(in) :: mean_pressure    !< p-bar (> 0, units of modulus)
      type(bem_options), intent(in) :: options !< tolerances, threads, outputs
      type(bem_state), intent(inout), target :: state  !< plans and warm start
      type(bem_result), intent(out) :: result  !< u, p-bar, area, iterations (+ fields)
      type(egw_error), allocatable, intent(out) :: error  !< set on failure
      call solve(heights, pixel, modulus, .true., mean_pressure, options, state, result, &
         & error)
   end subroutine bem_solve_load

   !> One gap-controlled solve: the contact of the map with the flat held at the mean
   !> separation `mean_separation` (> 0; at or above the highest height nothing touches).
   subroutine bem_solve_gap(heights, pixel, modulus, mean_separation, options, state, &
      & result, error)
      real(dp), intent(in) :: heights(:, :)    !< h(i, j), any length unit; periodic
      real(dp), intent(in) :: pixel            !< pixel size (> 0, same unit as heights)
      real(dp), intent(in) :: modulus          !< effective modulus E* (> 0)
      real(dp), intent(in) :: mean_separation  !< u (> 0, length unit of heights)
      type(bem_options), intent(in) :: options !< tolerances, threads, outputs
      type(bem_state), intent(inout), target :: state  !< plans and warm start
      type(bem_result), intent(out) :: result  !< u, p-bar, area, iterations (+ fields)
      type(egw_error), allocatable, intent(out) :: error  !< set on failure
      call solve(heights, pixel, modulus, .false., mean_separation, options, state, result, &
         & error)
   end subroutine bem_solve_gap

   !> The flat law of a map: load-controlled solves at mean pressures from p_min to p_max,
   !> geometric with `per_decade` loads per decade (both ends included), each warm-started
   !> from the one before, with the stiffness of each (the linear solve of the module
   !> header). The sweep ends before the first load that brings full contact (there
   !> u = 0 and the stiffness is infinite), so the arrays may be shorter than the plan.
   subroutine bem_flat_curve(heights, pixel, modulus, p_min, p_max, per_decade, options, &
      & u, p, area, stiffness, error)
      real(dp), intent(in) :: heights(:, :)    !< h(i, j), any length unit; periodic
      real(dp), intent(in) :: pixel            !< pixel size (> 0)
      real(dp), intent(in) :: modulus          !< effective modulus E* (> 0)
      real(dp), intent(in) :: p_min            !< smallest mean pressure (> 0, units of modulus)
      real(dp), intent(in) :: p_max            !< largest mean pressure (> p_min)
      integer, intent(in) :: per_decade        !< loads per decade (>= 1)
      type(bem_options), intent(in) :: options !< tolerances and threads (fields not kept)
      real(dp), allocatable, intent(out) :: u(:)         !< mean separations (decreasing)
      real(dp), allocatable, intent(out) :: p(:)         !< mean pressures (increasing)
      real(dp), allocatable, intent(out) :: area(:)      !< contact-area fractions
      real(dp), allocatable, intent(out) :: stiffness(:) !< -dp/du (units of modulus/length)
      type(egw_error), allocatable, intent(out) :: error !< set on failure
      type(bem_state) :: state
      type(bem_options) :: opts
      type(bem_result) :: res
      integer :: n, k, last
      real(dp), allocatable :: loads(:)
      if (.not. (ieee_is_finite(p_min) .and. p_min > 0.0_dp)) then
         call parameter_error(error, "p_min", p_min, "must be finite and > 0")
         return
      end if
      if (.not. (ieee_is_finite(p_max) .and. p_max > p_min)) then
         call parameter_error(error, "p_max", p_max, "must be finite and > p_min = " &
            & //format_real(p_min))
         return
      end if
      if (per_decade < 1 .or. per_decade > 1000) then
         call fatal_error(error, egw_invalid_argument, "per_decade = "//int_str(per_decade) &
            & //": must be in [1, 1000]")
         return
      end if
      n = max(2, ceiling(real(per_decade, dp)*log10(p_max/p_min) - 1.0e-9_dp) + 1)
      allocate (loads(n), u(n), p(n), area(n), stiffness(n))
      do k = 1, n
         loads(k) = p_min*(p_max/p_min)**(real(k - 1, dp)/real(n - 1, dp))
      end do
      loads(n) = p_max
      opts = options
      opts%keep_fields = .false.
      opts%stiffness = .true.
      last = 0
      do k = 1, n
         call bem_solve_load(heights, pixel, modulus, loads(k), opts, state, res, error)
         if (allocated(error)) then
            error%message = "bem_flat_curve: load "//int_str(k)//" of "//int_str(n)//": " &
               & //error%message
            exit
         end if
         if (res%area_fraction >= 1.0_dp) exit
         last = k
         u(k) = res%mean_separation
         p(k) = res%mean_pressure
         area(k) = res%area_fraction
         stiffness(k) = res%stiffness
      end do
      call bem_state_release(state)
      if (allocated(error)) then
         deallocate (u, p, area, stiffness)
         allocate (u(0), p(0), area(0), stiffness(0))
         return
      end if
      u = u(1:last)
      p = p(1:last)
      area = area(1:last)
      stiffness = stiffness(1:last)
   end subroutine bem_flat_curve

   !> The common body of the two solves.
   subroutine solve(heights, pixel, modulus, load, target, options, state, result, error)
      real(dp), intent(in) :: heights(:, :), pixel, modulus
      logical, intent(in) :: load      ! load control (target = p-bar), else gap (target = u)
      real(dp), intent(in) :: target
      type(bem_options), intent(in) :: options
      type(bem_state), intent(inout), target :: state
      type(bem_result), intent(out) :: result
      type(egw_error), allocatable, intent(out) :: error
      real(dp), allocatable :: h(:, :), p(:, :), w(:, :)
      real(dp) :: rms, u, npix
      integer :: nx, ny, nt, iters, st
      character(len=:), allocatable :: what

      nx = size(heights, 1)
      ny = size(heights, 2)
      if (load) then
         what = "mean_pressure"
      else
         what = "mean_separation"
      end if
      call check_input(heights, pixel, modulus, options, error)
      if (allocated(error)) return
      if (.not. (ieee_is_finite(target) .and. target > 0.0_dp)) then
         if (load) then
            call parameter_error(error, what, target, "must be finite and > 0")
         else
            call parameter_error(error, what, target, "must be finite and > 0 (at u = 0 a " &
               & //"periodic surface is in full contact under any load above its " &
               & //"full-contact load)")
         end if
         return
      end if
      nt = options%n_threads
      if (nt <= 0) then
         nt = 1
         !$ nt = omp_get_max_threads()
      end if
      npix = real(nx, dp)*real(ny, dp)
      ! a thread per 128^2 pixels at most: below that the ~20 parallel regions of a CG
      ! step cost more than they share, and on a busy machine far more (see Threads)
      nt = max(1, min(nt, int(npix/real(pixels_per_thread, dp))))
      allocate (h(nx, ny), p(nx, ny), w(nx, ny), stat=st)
      if (st /= 0) then
         call fatal_error(error, egw_out_of_memory, "heights: "//int_str(nx)//" x " &
            & //int_str(ny)//" pixels: out of memory")
         return
      end if
      h = heights - sum(heights)/npix
      rms = sqrt(sum(h**2)/npix)
      if (.not. (rms > 1.0e-13_dp*maxval(abs(heights)))) then
         call parameter_error(error, "rms height of heights", rms, "the heights are all " &
            & //"equal: a flat surface is in full contact at any load")
         return
      end if
      call prepare(state, nx, ny, pixel, modulus, nt, error)
      if (allocated(error)) return

      if (.not. load .and. target >= maxval(h)) then
         ! the flat does not reach the highest summit: no contact
         p = 0.0_dp
         u = target
         iters = 0
      else
         if (allocated(state%pressure)) then
            p = state%pressure
         else if (load) then
            p = target
         else
            p = 0.0_dp
         end if
         call pk_solve(state, h, rms, load, target, options, nt, p, u, iters, error)
         if (allocated(error)) then
            error%message = what//" = "//format_real(target)//": "//error%message
            return
         end if
         call move_alloc(p, state%pressure)
         p = state%pressure
      end if
      result%mean_separation = u
      result%mean_pressure = sum(p)/npix
      result%area_fraction = real(count(p > 0.0_dp), dp)/npix
      result%iterations = iters
      if (options%stiffness) then
         if (result%area_fraction >= 1.0_dp) then
            result%stiffness = huge(1.0_dp)
         else
            call contact_stiffness(state, p, options, nt, result%stiffness, error)
            if (allocated(error)) then
               error%message = what//" = "//format_real(target)//": "//error%message
               return
            end if
         end if
      end if
      if (options%keep_fields) then
         call respond(state, p, w, nt)
         result%gap = u - h + w
         call move_alloc(p, result%pressure)
      end if
   end subroutine solve

   !> Validate what every solve takes; errors name the parameter and its value.
   subroutine check_input(heights, pixel, modulus, options, error)
      real(dp), intent(in) :: heights(:, :), pixel, modulus
      type(bem_options), intent(in) :: options
      type(egw_error), allocatable, intent(out) :: error
      integer :: i, j
      if (size(heights, 1) < 1 .or. size(heights, 2) < 1 .or. size(heights) < 2) then
         call fatal_error(error, egw_invalid_argument, "heights: "//int_str(size(heights, 1)) &
            & //" x "//int_str(size(heights, 2))//" pixels: need at least 2 (a map 1 pixel " &
            & //"wide is a surface constant along that axis)")
         return
      end if
      do j = 1, size(heights, 2)
         do i = 1, size(heights, 1)
            if (.not. ieee_is_finite(heights(i, j))) then
               call parameter_error(error, "heights("//int_str(i)//", "//int_str(j)//")", &
                  & heights(i, j), "must be finite")
               return
            end if
         end do
      end do
      if (.not. (ieee_is_finite(pixel) .and. pixel > 0.0_dp)) then
         call parameter_error(error, "pixel", pixel, "must be finite and > 0")
         return
      end if
      if (.not. (ieee_is_finite(modulus) .and. modulus > 0.0_dp)) then
         call parameter_error(error, "modulus", modulus, "must be finite and > 0")
         return
      end if
      if (.not. (options%tolerance >= 1.0e-15_dp .and. options%tolerance <= 1.0e-2_dp)) then
         call fatal_error(error, egw_invalid_argument, "options%tolerance = " &
            & //format_real(options%tolerance)//": must be in [1e-15, 1e-2]")
         return
      end if
      if (.not. (options%stiffness_tolerance >= 1.0e-15_dp .and. &
         & options%stiffness_tolerance <= 1.0e-2_dp)) then
         call fatal_error(error, egw_invalid_argument, "options%stiffness_tolerance = " &
            & //format_real(options%stiffness_tolerance)//": must be in [1e-15, 1e-2]")
         return
      end if
      if (options%max_iter < 1) then
         call fatal_error(error, egw_invalid_argument, "options%max_iter = " &
            & //int_str(options%max_iter)//": must be >= 1")
         return
      end if
      if (options%n_threads < 0) then
         call fatal_error(error, egw_invalid_argument, "options%n_threads = " &
            & //int_str(options%n_threads)//": must be >= 0 (0: OpenMP's default)")
         return
      end if
   end subroutine check_input

   !> Buffers, compliance and FFT plans of the grid (re)made when the grid, the pixel,
   !> the modulus or the thread count changed, or when the state was copied.
   subroutine prepare(state, nx, ny, pixel, modulus, nt, error)
      type(bem_state), intent(inout), target :: state
      integer, intent(in) :: nx, ny, nt
      real(dp), intent(in) :: pixel, modulus
      type(egw_error), allocatable, intent(out) :: error
      integer :: st, i, j, kx, ky
      real(dp) :: q, lx, ly, weight
      logical :: planned
      if (state%nx /= nx .or. state%ny /= ny .or. .not. allocated(state%compliance)) then
         call release_plans(state)
         if (allocated(state%compliance)) deallocate (state%compliance)
         if (allocated(state%real_buffer)) deallocate (state%real_buffer)
         if (allocated(state%spectrum)) deallocate (state%spectrum)
         if (allocated(state%pressure)) deallocate (state%pressure)
         if (allocated(state%response)) deallocate (state%response)
         allocate (state%compliance(nx/2 + 1, ny), state%real_buffer(nx, ny), &
            & state%spectrum(nx/2 + 1, ny), stat=st)
         if (st /= 0) then
            call fatal_error(error, egw_out_of_memory, "heights: "//int_str(nx)//" x " &
               & //int_str(ny)//" pixels: out of memory for the FFT buffers")
            return
         end if
         state%nx = nx
         state%ny = ny
         state%pixel = -1.0_dp
      end if
      if (pixel /= state%pixel .or. modulus /= state%modulus) then
         lx = real(nx, dp)*pixel
         ly = real(ny, dp)*pixel
         state%self_compliance = 0.0_dp
         do j = 1, ny
            ky = j - 1
            if (ky > ny/2) ky = ky - ny
            do i = 1, nx/2 + 1
               kx = i - 1
               q = 2.0_dp*pi*sqrt((real(kx, dp)/lx)**2 + (real(ky, dp)/ly)**2)
               if (kx == 0 .and. ky == 0) then
                  state%compliance(i, j) = 0.0_dp
               else
                  state%compliance(i, j) = 2.0_dp/(modulus*q)/(real(nx, dp)*real(ny, dp))
               end if
               ! the half-spectrum stands for both kx and -kx but at 0 and nx/2
               weight = 2.0_dp
               if (kx == 0 .or. 2*kx == nx) weight = 1.0_dp
               state%self_compliance = state%self_compliance + weight*state%compliance(i, j)
            end do
         end do
         state%pixel = pixel
         state%modulus = modulus
      end if
      planned = c_associated(state%forward) .and. c_associated(state%backward) .and. &
         & c_associated(state%planned_buffer, c_loc(state%real_buffer))
      if (planned .and. state%threads == nt) return
      if (planned) call release_plans(state)
      !$omp critical (egw_fftw_planner)
      if (.not. fftw_threads_ready) then
         if (fftw_init_threads() /= 0_c_int) fftw_threads_ready = .true.
      end if
      if (fftw_threads_ready) call fftw_plan_with_nthreads(int(nt, c_int))
      state%forward = fftw_plan_dft_r2c_2d(int(ny, c_int), int(nx, c_int), &
         & state%real_buffer, state%spectrum, fftw_estimate_flag)
      state%backward = fftw_plan_dft_c2r_2d(int(ny, c_int), int(nx, c_int), &
         & state%spectrum, state%real_buffer, ior(fftw_estimate_flag, fftw_destroy_input_flag))
      !$omp end critical (egw_fftw_planner)
      state%planned_buffer = c_loc(state%real_buffer)
      state%threads = nt
      if (.not. (c_associated(state%forward) .and. c_associated(state%backward))) then
         call fatal_error(error, egw_out_of_memory, "heights: "//int_str(nx)//" x " &
            & //int_str(ny)//" pixels: FFTW could not make a plan")
      end if
   end subroutine prepare

   !> Destroy the state's plans if it owns them (made on its own buffer: a copied state
   !> holds the handles of the original and must not destroy them).
   subroutine release_plans(state)
      type(bem_state), intent(inout), target :: state
      logical :: owned
      owned = .false.
      if (allocated(state%real_buffer)) owned = &
         & c_associated(state%planned_buffer, c_loc(state%real_buffer))
      if (owned) then
         !$omp critical (egw_fftw_planner)
         if (c_associated(state%forward)) call fftw_destroy_plan(state%forward)
         if (c_associated(state%backward)) call fftw_destroy_plan(state%backward)
         !$omp end critical (egw_fftw_planner)
      end if
      state%forward = c_null_ptr
      state%backward = c_null_ptr
      state%planned_buffer = c_null_ptr
   end subroutine release_plans

   !> Release the FFTW plans a state made (call when done with it; bem_flat_curve does for
   !> its own). Not a finaliser: gfortran 12 finalises such derived types where the
   !> standard does not (a release build crashed destroying plans twice).
   subroutine bem_state_release(state)
      !> its plans destroyed; the state is not used again
      type(bem_state), intent(inout), target :: state
      call release_plans(state)
   end subroutine bem_state_release

   !> y = G x: the zero-mean surface displacement under the pixel pressures x.
   subroutine respond(state, x, y, nt)
      type(bem_state), intent(inout) :: state
      real(dp), intent(in) :: x(:, :)
      real(dp), intent(out) :: y(:, :)
      integer, intent(in) :: nt
      integer :: j
      !$omp parallel do num_threads(nt) schedule(static)
      do j = 1, state%ny
         state%real_buffer(:, j) = x(:, j)
      end do
      !$omp end parallel do
      call fftw_execute(state%forward)
      !$omp parallel do num_threads(nt) schedule(static)
      do j = 1, state%ny
         state%spectrum(:, j) = state%spectrum(:, j)*state%compliance(:, j)
      end do
      !$omp end parallel do
      call fftw_execute(state%backward)
      !$omp parallel do num_threads(nt) schedule(static)
      do j = 1, state%ny
         y(:, j) = state%real_buffer(:, j)
      end do
      !$omp end parallel do
   end subroutine respond

   !> Constrained conjugate gradients (Polonsky & Keer 1999) from the pressure p; on
   !> return p is the converged pressure and u the mean separation.
   subroutine pk_solve(state, h, rms, load, target, options, nt, p, u, iters, error)
      type(bem_state), intent(inout) :: state
      real(dp), intent(in) :: h(:, :), rms, target
      logical, intent(in) :: load
      type(bem_options), intent(in) :: options
      integer, intent(in) :: nt
      real(dp), intent(inout) :: p(:, :)
      real(dp), intent(out) :: u
      integer, intent(out) :: iters
      type(egw_error), allocatable, intent(out) :: error
      real(dp), allocatable :: w(:, :), g(:, :), t(:, :), r(:, :)
      logical, allocatable :: inside(:, :)
      real(dp) :: npix, gsum, residual, gg, gg_old, beta, rsum, tsum, num, den, tau, scale
      integer :: nx, ny, i, j, it, st
      integer(kind=8) :: ncontact
      logical :: restart

      nx = size(h, 1)
      ny = size(h, 2)
      npix = real(nx, dp)*real(ny, dp)
      allocate (w(nx, ny), g(nx, ny), t(nx, ny), r(nx, ny), inside(nx, ny), stat=st)
      if (st /= 0) then
         call fatal_error(error, egw_out_of_memory, "out of memory for the CG fields")
         return
      end if
      t = 0.0_dp
      p = max(p, 0.0_dp)
      if (load) call rescale(p, target, npix)
      u = target
      restart = .true.
      gg_old = 1.0_dp
      residual = huge(1.0_dp)
      call respond(state, p, w, nt)
      iters = 0
      do it = 0, options%max_iter
         iters = it
         ! P&K step 2: the rigid approach that zeroes the mean gap on the contact set
         if (load) then
            gsum = 0.0_dp
            ncontact = 0
            !$omp parallel do num_threads(nt) schedule(static) reduction(+:gsum, ncontact)
            do j = 1, ny
               do i = 1, nx
                  if (p(i, j) > 0.0_dp) then
                     gsum = gsum + (w(i, j) - h(i, j))
                     ncontact = ncontact + 1
                  end if
               end do
            end do
            !$omp end parallel do
            u = -gsum/real(max(ncontact, 1_8), dp)
         end if
         ! the gap, the residual of the contact conditions, G = sum g^2 on the contact set
         residual = 0.0_dp
         gg = 0.0_dp
         ncontact = 0
         !$omp parallel do num_threads(nt) schedule(static) &
         !$omp & reduction(+:gg, ncontact) reduction(max:residual)
         do j = 1, ny
            do i = 1, nx
               g(i, j) = u - h(i, j) + w(i, j)
               inside(i, j) = p(i, j) > 0.0_dp
               if (inside(i, j)) then
                  residual = max(residual, abs(g(i, j)))
                  gg = gg + g(i, j)**2
                  ncontact = ncontact + 1
               else
                  residual = max(residual, -g(i, j))
               end if
            end do
         end do
         !$omp end parallel do
         if (residual <= options%tolerance*rms) return
         if (it == options%max_iter) exit
         if (ncontact == 0) then
            ! gap control from no contact: a Jacobi guess from the penetration
            p = max(-g, 0.0_dp)/state%self_compliance
            restart = .true.
            call respond(state, p, w, nt)
            cycle
         end if
         ! P&K step 4: the conjugate direction on the contact set
         beta = 0.0_dp
         if (.not. restart) beta = gg/gg_old
         gg_old = gg
         !$omp parallel do num_threads(nt) schedule(static)
         do j = 1, ny
            do i = 1, nx
               if (inside(i, j)) then
                  t(i, j) = g(i, j) + beta*t(i, j)
               else
                  t(i, j) = 0.0_dp
               end if
            end do
         end do
         !$omp end parallel do
         ! P&K steps 5-6: its displacement (minus its contact-set mean under load
         ! control) and the step length
         call respond(state, t, r, nt)
         rsum = 0.0_dp
         tsum = 0.0_dp
         num = 0.0_dp
         den = 0.0_dp
         !$omp parallel do num_threads(nt) schedule(static) reduction(+:rsum, tsum, num, den)
         do j = 1, ny
            do i = 1, nx
               if (inside(i, j)) then
                  rsum = rsum + r(i, j)
                  tsum = tsum + t(i, j)
                  num = num + g(i, j)*t(i, j)
                  den = den + r(i, j)*t(i, j)
               end if
            end do
         end do
         !$omp end parallel do
         ! sum (r - mean r) t over the contact set under load control
         if (load) den = den - rsum/real(ncontact, dp)*tsum
         tau = 0.0_dp
         if (den > 0.0_dp) tau = num/den
         ! P&K steps 7-10: the step, p >= 0, penetrating pixels added, the load
         scale = tau
         if (.not. (scale > 0.0_dp)) scale = 1.0_dp/state%self_compliance
         call pk_step(p, g, t, inside, tau, scale, load, target, npix, nt, restart)
         if (.not. (den > 0.0_dp)) restart = .true.
         call respond(state, p, w, nt)
      end do
      call fatal_error(error, egw_not_converged, "not converged after options%max_iter = " &
         & //int_str(options%max_iter)//" steps: gap residual "//format_real(residual/rms) &
         & //" of the rms height, options%tolerance = "//format_real(options%tolerance))
   end subroutine pk_solve

   !> P&K steps 7-10: p - tau t on the contact set, clipped at 0; pixels that penetrate
   !> without pressure get -scale g (restart = .true. then); under load control p is
   !> rescaled to the mean `target`.
   subroutine pk_step(p, g, t, inside, tau, scale, load, target, npix, nt, restart)
      real(dp), intent(inout) :: p(:, :)
      real(dp), intent(in) :: g(:, :), t(:, :), tau, scale, target, npix
      logical, intent(in) :: inside(:, :), load
      integer, intent(in) :: nt
      logical, intent(out) :: restart
      real(dp) :: psum
      integer :: i, j
      logical :: added
      added = .false.
      psum = 0.0_dp
      !$omp parallel do num_threads(nt) schedule(static) reduction(.or.:added) &
      !$omp & reduction(+:psum)
      do j = 1, size(p, 2)
         do i = 1, size(p, 1)
            if (inside(i, j)) p(i, j) = max(p(i, j) - tau*t(i, j), 0.0_dp)
            if (p(i, j) <= 0.0_dp .and. g(i, j) < 0.0_dp) then
               p(i, j) = -scale*g(i, j)
               added = .true.
            end if
            psum = psum + p(i, j)
         end do
      end do
      !$omp end parallel do
      restart = added
      if (.not. load) return
      if (psum > 0.0_dp) then
         !$omp parallel do num_threads(nt) schedule(static)
         do j = 1, size(p, 2)
            p(:, j) = p(:, j)*(target*npix/psum)
         end do
         !$omp end parallel do
      else
         p = target
         restart = .true.
      end if
   end subroutine pk_step

   !> p scaled to the mean `target` (uniform if it carries nothing).
   pure subroutine rescale(p, target, npix)
      real(dp), intent(inout) :: p(:, :)
      real(dp), intent(in) :: target, npix
      real(dp) :: psum
      psum = sum(p)
      if (psum > 0.0_dp) then
         p = p*(target*npix/psum)
      else
         p = target
      end if
   end subroutine rescale

   !> -dp-bar/du with the contact set of p held: (G x)_i = 1 on the contact set by CG,
   !> warm-started from the state's last solution, k = mean(x).
   subroutine contact_stiffness(state, p, options, nt, k, error)
      type(bem_state), intent(inout) :: state
      real(dp), intent(in) :: p(:, :)
      type(bem_options), intent(in) :: options
      integer, intent(in) :: nt
      real(dp), intent(out) :: k
      type(egw_error), allocatable, intent(out) :: error
      real(dp), allocatable :: x(:, :), r(:, :), d(:, :), q(:, :)
      real(dp) :: rr, rr_new, dq, alpha, bnorm
      integer :: nx, ny, i, j, it
      nx = size(p, 1)
      ny = size(p, 2)
      allocate (x(nx, ny), r(nx, ny), d(nx, ny), q(nx, ny))
      x = 0.0_dp
      if (allocated(state%response)) x = state%response
      where (.not. p > 0.0_dp) x = 0.0_dp
      call respond(state, x, q, nt)
      where (p > 0.0_dp)
         r = 1.0_dp - q
      elsewhere
         r = 0.0_dp
      end where
      bnorm = sqrt(real(count(p > 0.0_dp), dp))
      d = r
      rr = sum(r**2)
      do it = 1, options%max_iter
         if (sqrt(rr) <= options%stiffness_tolerance*bnorm) exit
         call respond(state, d, q, nt)
         dq = 0.0_dp
         !$omp parallel do num_threads(nt) schedule(static) reduction(+:dq)
         do j = 1, ny
            do i = 1, nx
               if (p(i, j) > 0.0_dp) dq = dq + d(i, j)*q(i, j)
            end do
         end do
         !$omp end parallel do
         if (.not. (dq > 0.0_dp)) exit
         alpha = rr/dq
         rr_new = 0.0_dp
         !$omp parallel do num_threads(nt) schedule(static) reduction(+:rr_new)
         do j = 1, ny
            do i = 1, nx
               if (p(i, j) > 0.0_dp) then
                  x(i, j) = x(i, j) + alpha*d(i, j)
                  r(i, j) = r(i, j) - alpha*q(i, j)
                  rr_new = rr_new + r(i, j)**2
               end if
            end do
         end do
         !$omp end parallel do
         d = r + (rr_new/rr)*d
         rr = rr_new
      end do
      if (sqrt(rr) > options%stiffness_tolerance*bnorm) then
         call fatal_error(error, egw_not_converged, "stiffness solve not converged after " &
            & //"options%max_iter = "//int_str(options%max_iter)//" steps: relative " &
            & //"residual "//format_real(sqrt(rr)/bnorm)//", options%stiffness_tolerance = " &
            & //format_real(options%stiffness_tolerance))
         return
      end if
      k = sum(x)/(real(nx, dp)*real(ny, dp))
      call move_alloc(x, state%response)
   end subroutine contact_stiffness

end module egw_flat_bem
