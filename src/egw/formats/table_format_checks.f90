!> The checks every reader of egw_table_format runs before it hands over a table, and
!> the small helpers the format submodules share (separate module procedures: gfortran
!> drops private procedures of a module that only its submodules call).
submodule (egw_table_format) egw_table_format_checks
   use egw_table, only: gl_x, gl_w
   implicit none

   !> The largest node value (overlap, force, stiffness, energy, contact radius, in the
   !> table's units) a reader accepts. No contact comes near it in any units (a steel ball
   !> of 1 km pressed 1 m carries ~1e17 N; in SI, pN or light-years the exponents shift
   !> by tens), and it leaves ~1e100 of room below the largest double for what evaluation
   !> derives from a node: products with overlaps, energies, the deep-overlap law above
   !> delta_max. A file with a node force of 1e300 and a valid checksum is refused.
   real(dp), parameter :: absurd_value = 1.0e200_dp

contains

   module procedure check_table
      integer :: n, i
      character(len=:), allocatable :: field
      n = size(t%delta)
      if (n < 2) then
         call bad(error, path, where//"fewer than 2 nodes")
         return
      end if
      call check_meta(path, where, t, error)
      if (allocated(error)) return
      do i = 1, n
         if (.not. row_ok([t%delta(i), t%force(i), t%stiffness(i), t%energy(i), &
            & t%contact_radius(i)])) then
            call bad(error, path, where//"node "//int_str(i)//" is not finite")
            return
         end if
         if (t%force(i) < 0.0_dp) then
            call bad(error, path, where//"node "//int_str(i)//": negative force "// &
               & format_real(t%force(i)))
            return
         end if
         if (t%stiffness(i) < 0.0_dp) then
            call bad(error, path, where//"node "//int_str(i)//": negative stiffness "// &
               & format_real(t%stiffness(i)))
            return
         end if
         if (t%energy(i) < 0.0_dp) then
            call bad(error, path, where//"node "//int_str(i)//": negative energy "// &
               & format_real(t%energy(i)))
            return
         end if
         if (t%contact_radius(i) < 0.0_dp) then
            call bad(error, path, where//"node "//int_str(i)//": negative contact "// &
               & "radius "//format_real(t%contact_radius(i)))
            return
         end if
         if (i == 1) cycle
         if (t%force(i) < t%force(i - 1)) then
            call bad(error, path, where//"node "//int_str(i)//": force "// &
               & format_real(t%force(i))//" below the previous node's "// &
               & format_real(t%force(i - 1))//" (the force must not decrease)")
            return
         end if
         if (t%energy(i) < t%energy(i - 1)) then
            call bad(error, path, where//"node "//int_str(i)//": energy decreases")
            return
         end if
      end do
      if (any(t%delta(2:n) <= t%delta(1:n - 1))) then
         call bad(error, path, where//"delta is not strictly increasing")
         return
      end if
      if (t%n_log < 0 .or. t%n_log > n - 1) then
         call bad(error, path, where//"n_log = "//int_str(t%n_log)//" out of range")
         return
      end if
      if (t%n_log > 0) then
         if (any(t%force(1:t%n_log + 1) <= 0.0_dp)) then
            call bad(error, path, where//"log-space interval with a zero force")
            return
         end if
      end if
      if (t%cutoff /= t%delta(1) .or. t%delta_max /= t%delta(n)) then
         call bad(error, path, where//"cutoff/delta_max disagree with the nodes")
         return
      end if
      if (t%energy(1) /= 0.0_dp) then
         call bad(error, path, where//"energy at the cut-off "//format_real(t%energy(1))// &
            & ": must be 0 (it is the integral from the cut-off)")
         return
      end if
      do i = 1, n - 1
         call check_interval(path, where, t, i, error)
         if (allocated(error)) return
         if (i > t%n_log) call check_positive_cubic(path, where, t, i, error)
         if (allocated(error)) return
         call check_energy_integral(path, where, t, i, error)
         if (allocated(error)) return
      end do
      ! last: values that pass every check above but no contact has
      do i = 1, n
         if (maxval(abs([t%delta(i), t%force(i), t%stiffness(i), t%energy(i), &
            & t%contact_radius(i)])) > absurd_value) then
            call absurd_field(t, i, field)
            call bad(error, path, where//"node "//int_str(i)//": "// &
               & field//" above "//format_real(absurd_value)// &
               & " (no contact reaches it in any units; the continuations would overflow)")
            return
         end if
      end do
   end procedure check_table

   !> The first of the node's values above absurd_value, as "name value".
   subroutine absurd_field(t, i, text)
      type(force_table), intent(in) :: t
      integer, intent(in) :: i
      character(len=:), allocatable, intent(out) :: text
      if (abs(t%delta(i)) > absurd_value) then
         text = "delta "//format_real(t%delta(i))
      else if (abs(t%force(i)) > absurd_value) then
         text = "force "//format_real(t%force(i))
      else if (abs(t%stiffness(i)) > absurd_value) then
         text = "stiffness "//format_real(t%stiffness(i))
      else if (abs(t%energy(i)) > absurd_value) then
         text = "energy "//format_real(t%energy(i))
      else
         text = "contact_radius "//format_real(t%contact_radius(i))
      end if
   end subroutine absurd_field

   !> An interval that interpolates P itself (i > n_log) must not dip below 0: its Hermite
   !> cubic's least value on [0, 1] (at an end or where its derivative vanishes) at least
   !> -64 eps of its larger end (round-off). The builder's cubics are monotone
   !> (Fritsch-Carlson) and never dip; a file whose n_log was lowered, so that the
   !> separated tail is read as P rather than ln P, would (issue 33: negative forces
   !> below the cut-off's neighbours).
   subroutine check_positive_cubic(path, where, t, i, error)
      character(len=*), intent(in) :: path, where
      type(force_table), intent(in) :: t
      integer, intent(in) :: i
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: h, c(0:3), disc, roots(2), low, v
      integer :: r
      h = t%delta(i + 1) - t%delta(i)
      c(0) = t%force(i)
      c(1) = h*t%stiffness(i)
      c(2) = 3*(t%force(i + 1) - t%force(i)) - 2*h*t%stiffness(i) - h*t%stiffness(i + 1)
      c(3) = 2*(t%force(i) - t%force(i + 1)) + h*t%stiffness(i) + h*t%stiffness(i + 1)
      low = min(t%force(i), t%force(i + 1))
      ! v'(u) = c1 + 2 c2 u + 3 c3 u^2
      roots = -1.0_dp
      if (c(3) /= 0.0_dp) then
         disc = c(2)**2 - 3*c(3)*c(1)
         if (disc >= 0.0_dp) roots = [(-c(2) - sqrt(disc))/(3*c(3)), &
            & (-c(2) + sqrt(disc))/(3*c(3))]
      else if (c(2) /= 0.0_dp) then
         roots(1) = -c(1)/(2*c(2))
      end if
      do r = 1, 2
         if (roots(r) > 0.0_dp .and. roots(r) < 1.0_dp) then
            v = c(0) + roots(r)*(c(1) + roots(r)*(c(2) + roots(r)*c(3)))
            low = min(low, v)
         end if
      end do
      if (low < -64*epsilon(1.0_dp)*max(t%force(i), t%force(i + 1))) then
         call bad(error, path, where//"nodes "//int_str(i)//", "//int_str(i + 1)// &
            & ": the force interpolated between them falls to "//format_real(low)// &
            & " (negative; n_log = "//int_str(t%n_log)//": is the separated tail "// &
            & "interpolated in P instead of ln P?)")
      end if
   end subroutine check_positive_cubic

   module procedure check_universal_header
      if (u%n_mu < 4 .or. u%n_mu > 100000) then
         call bad(error, path, "n_mu = "//int_str(u%n_mu)//": need at least 4")
      else if (.not. (u%rel_tol > 0.0_dp .and. u%rel_tol <= 0.1_dp)) then
         call bad(error, path, "rel_tol = "//format_real(u%rel_tol)//": must lie in (0, 0.1]")
      else if (.not. (ieee_is_finite(u%max_mu_error) .and. u%max_mu_error >= 0)) then
         call bad(error, path, "max_mu_error = "//format_real(u%max_mu_error)// &
            & ": must be finite and >= 0")
      else if (.not. (ieee_is_finite(u%x_cut) .and. ieee_is_finite(u%x_max) .and. &
         & u%x_cut < u%x_max)) then
         call bad(error, path, "x_cut = "//format_real(u%x_cut)//", x_max = "// &
            & format_real(u%x_max)//": need finite x_cut < x_max")
      else if (.not. (ieee_is_finite(u%mu_min) .and. u%mu_min > 0.0_dp .and. &
         & ieee_is_finite(u%mu_max) .and. u%mu_max > u%mu_min)) then
         call bad(error, path, "mu range ["//format_real(u%mu_min)//", "// &
            & format_real(u%mu_max)//"] invalid")
      else
         call validate_params(universal_slice_params(u%model, u%psi, u%hardness_coeff, &
            & u%plastic_ratio, u%mu_min), error)
         if (allocated(error)) call bad(error, path, "stored parameters invalid: "// &
            & error%message)
      end if
   end procedure check_universal_header

   module procedure check_universal_slices
      integer :: j
      do j = 1, u%n_mu
         if (u%slices(j)%cutoff /= u%x_cut .or. u%slices(j)%delta_max /= u%x_max) then
            call bad(error, path, "slice "//int_str(j)//": range differs from x_cut, x_max")
            return
         end if
      end do
      if (.not. universal_nodes_shared(u)) then
         call bad(error, path, "slices do not share their nodes or ln p intervals")
         return
      end if
      if (u%model == model_hertz) call check_universal_hertz(path, u, error)
   end procedure check_universal_slices

   !> A universal table labelled Hertz (model = 0) must hold Hertz's data, or a relabelled
   !> rough table would serve its forces, tail below delta = 0 included, to Hertz contacts
   !> (Stop 50 audit16): Hertz has no force at x <= 0, so no ln p (tail) intervals, and its
   !> force does not depend on mu, so every slice is the first (the build's slices are
   !> equal bit for bit; 1e-12 of the largest force allows a text round trip's last bit).
   subroutine check_universal_hertz(path, u, error)
      character(len=*), intent(in) :: path
      type(universal_table), intent(in) :: u
      type(egw_error), allocatable, intent(out) :: error
      integer :: j, i
      real(dp) :: tol
      if (u%slices(1)%n_log /= 0) then
         call bad(error, path, "model = 0 (Hertz) does not fit the data: the slices have "// &
            & int_str(u%slices(1)%n_log)//" ln p (separated tail) intervals; Hertz has no "// &
            & "force below delta = 0")
         return
      end if
      do j = 1, u%n_mu
         do i = 1, size(u%slices(j)%delta)
            if (u%slices(j)%delta(i) <= 0.0_dp .and. u%slices(j)%force(i) /= 0.0_dp) then
               call bad(error, path, "model = 0 (Hertz) does not fit the data: slice "// &
                  & int_str(j)//" node "//int_str(i)//" has force "// &
                  & format_real(u%slices(j)%force(i))//" at x = "// &
                  & format_real(u%slices(j)%delta(i))//" <= 0; Hertz has none there")
               return
            end if
         end do
      end do
      tol = 1.0e-12_dp*maxval(abs(u%slices(1)%force))
      do j = 2, u%n_mu
         i = maxloc(abs(u%slices(j)%force - u%slices(1)%force), 1)
         if (abs(u%slices(j)%force(i) - u%slices(1)%force(i)) > tol) then
            call bad(error, path, "model = 0 (Hertz) does not fit the data: slice "// &
               & int_str(j)//" (mu = "//format_real(slice_mu(u, j))//") differs from "// &
               & "slice 1 at node "//int_str(i)//" ("//format_real(u%slices(j)%force(i))// &
               & " against "//format_real(u%slices(1)%force(i))//"); Hertz's force does "// &
               & "not depend on mu")
            return
         end if
      end do
   end subroutine check_universal_hertz

   module procedure slice_mu
      if (j == 1) then
         slice_mu = u%mu_min
      else if (j == u%n_mu) then
         slice_mu = u%mu_max
      else
         slice_mu = exp(log(u%mu_min) + (log(u%mu_max) - log(u%mu_min))*(j - 1)/(u%n_mu - 1))
      end if
   end procedure slice_mu

   module procedure move_table
      to%params = from%params
      to%rel_tol = from%rel_tol
      to%cutoff = from%cutoff
      to%delta_max = from%delta_max
      to%reference_force = from%reference_force
      to%max_force_error = from%max_force_error
      to%max_stiffness_error = from%max_stiffness_error
      to%radius_sum = from%radius_sum
      to%n_log = from%n_log
      to%checksum_missing = from%checksum_missing
      to%n_bucket = from%n_bucket
      to%bucket_scale = from%bucket_scale
      to%bucket_origin = from%bucket_origin
      to%crowded = from%crowded
      to%zero_below = from%zero_below
      call move_alloc(from%delta, to%delta)
      call move_alloc(from%force, to%force)
      call move_alloc(from%stiffness, to%stiffness)
      call move_alloc(from%energy, to%energy)
      call move_alloc(from%contact_radius, to%contact_radius)
      call move_alloc(from%seg, to%seg)
      call move_alloc(from%fine_seg, to%fine_seg)
      to%fine_scale = from%fine_scale
      to%tail_end = from%tail_end
      to%deep = from%deep
      call move_alloc(from%radius_slope, to%radius_slope)
      call move_alloc(from%bucket, to%bucket)
   end procedure move_table

   module procedure row_ok
      row_ok = all(ieee_is_finite(v))
   end procedure row_ok

   module procedure fmt
      str = real_text(x, 17, 3)  ! ES25.17E3
   end procedure fmt

   module procedure starts_with
      starts_with = .false.
      if (len(str) >= len(prefix)) starts_with = str(1:len(prefix)) == prefix
   end procedure starts_with

   !> What interval i of a table must satisfy beyond the signs of its nodes, so that no
   !> checksummed but crafted (or mis-built) file evaluates to nonsense: its end slopes
   !> (d = K, or K/P where the interval interpolates ln P) at most slope_bound times the
   !> secant's, so that the cubic stays within (slope_bound - 1)/4 of the secant's rise
   !> of the chord (the builder keeps alpha^2 + beta^2 <= 9, Fritsch-Carlson: a bound
   !> 10 is generous); where the data differ by round-off only, the rise the slopes give
   !> over the interval at most 1e-6 of the force; and the energy rise the integral of
   !> such a cubic can have: between h (P_0 - dP) and h (P_1 + dP) (ln P intervals:
   !> h P_0 exp(-2.25 d ln P) and h P_1 exp(2.25 d ln P)), up to the rounding of W.
   subroutine check_interval(path, where, t, i, error)
      character(len=*), intent(in) :: path, where
      type(force_table), intent(in) :: t
      integer, intent(in) :: i
      type(egw_error), allocatable, intent(out) :: error
      !> largest end slope over the secant slope (alpha, beta) a reader accepts
      real(dp), parameter :: slope_bound = 10.0_dp
      real(dp) :: h, p0, p1, d0, d1, rise, w_lo, w_hi, w_rise, slack, spread
      logical :: in_log
      in_log = i <= t%n_log
      h = t%delta(i + 1) - t%delta(i)
      p0 = t%force(i)
      p1 = t%force(i + 1)
      if (in_log) then
         rise = log(p1) - log(p0)
         d0 = h*t%stiffness(i)/p0
         d1 = h*t%stiffness(i + 1)/p1
      else
         rise = p1 - p0
         d0 = h*t%stiffness(i)
         d1 = h*t%stiffness(i + 1)
      end if
      if (p1 - p0 <= 1.0e3_dp*epsilon(1.0_dp)*p1) then
         ! round-off apart: no secant to compare with; the slopes may not move the force
         if (max(d0, d1) > merge(1.0e-6_dp, 1.0e-6_dp*p1, in_log)) then
            call bad(error, path, where//"nodes "//int_str(i)//", "//int_str(i + 1)// &
               & ": equal forces "//format_real(p1)//" with stiffness "// &
               & format_real(max(t%stiffness(i), t%stiffness(i + 1))))
            return
         end if
      else if (max(d0, d1) > slope_bound*rise) then
         call bad(error, path, where//"nodes "//int_str(i)//", "//int_str(i + 1)// &
            & ": stiffness "//format_real(max(t%stiffness(i), t%stiffness(i + 1)))// &
            & " inconsistent with the forces "//format_real(p0)//", "//format_real(p1)// &
            & " (end slopes more than "//format_real(slope_bound)//" times the secant's)")
         return
      else if (slope_bound*max(d0, d1) < rise) then
         ! a loading force has no stiffness peak inside an interval: the larger end slope
         ! is at least the secant's (built tables: >= 1.000, measured); a forged force jump
         ! with the stiffnesses kept is a step the cubic draws and no contact has
         call bad(error, path, where//"nodes "//int_str(i)//", "//int_str(i + 1)// &
            & ": the forces "//format_real(p0)//", "//format_real(p1)//" rise more than "// &
            & format_real(slope_bound)//" times what the stiffnesses "// &
            & format_real(t%stiffness(i))//", "//format_real(t%stiffness(i + 1))// &
            & " give over "//format_real(h)//" (a force jump between them)")
         return
      end if
      if (in_log) then
         spread = exp(min(2.25_dp*rise, 700.0_dp))
         w_lo = h*p0/spread
         w_hi = h*p1*spread
      else
         w_lo = h*(p0 - rise)
         w_hi = h*(p1 + rise)
      end if
      w_rise = t%energy(i + 1) - t%energy(i)
      slack = 1.0e-9_dp*w_hi + 64*epsilon(1.0_dp)*abs(t%energy(i + 1))
      if (w_rise < w_lo - slack .or. w_rise > w_hi + slack) then
         call bad(error, path, where//"nodes "//int_str(i)//", "//int_str(i + 1)// &
            & ": energy rise "//format_real(w_rise)//" inconsistent with the forces "// &
            & format_real(p0)//", "//format_real(p1)//" over "//format_real(h))
      end if
   end subroutine check_interval

   !> The writer's energies are the integrals of the interpolant (table_prepare): exact in
   !> P intervals (Hermite's rule h (P_0 + P_1)/2 + h^2 (K_0 - K_1)/12), in ln P ones the
   !> resampled tail's, within rel_tol/2 of the ln P cubic's (8-point Gauss-Legendre, as
   !> table_prepare). check_interval's energy bounds grow with the force jump itself (a
   !> last node's force x1e6 with a stiffness to match passed them); the integral of the
   !> cubic through the nodes follows a forged force, the stored energy does not unless it
   !> is forged with it. Tolerance rel_tol h max(P) (built tables: < 6e-12 of h max(P) in
   !> P intervals, measured) plus the rounding of W. Run after check_interval, whose
   !> slope bounds keep the cubic's exponent finite.
   subroutine check_energy_integral(path, where, t, i, error)
      character(len=*), intent(in) :: path, where
      type(force_table), intent(in) :: t
      integer, intent(in) :: i
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: h, p0, p1, rise, d0, d1, c2, c3, u, w_int, w_rise, slack
      integer :: q
      h = t%delta(i + 1) - t%delta(i)
      p0 = t%force(i)
      p1 = t%force(i + 1)
      if (i > t%n_log) then
         w_int = h*(p0 + p1)/2 + h*h*(t%stiffness(i) - t%stiffness(i + 1))/12
      else
         ! ln P(u) = ln P_0 + d0 u + c2 u^2 + c3 u^3 on u in [0, 1]
         rise = log(p1) - log(p0)
         d0 = h*t%stiffness(i)/p0
         d1 = h*t%stiffness(i + 1)/p1
         c2 = 3*rise - 2*d0 - d1
         c3 = d0 + d1 - 2*rise
         w_int = 0.0_dp
         do q = 1, size(gl_x)
            u = gl_x(q)
            w_int = w_int + gl_w(q)*exp(min(u*(d0 + u*(c2 + u*c3)), 700.0_dp))
         end do
         w_int = w_int*h*p0
      end if
      w_rise = t%energy(i + 1) - t%energy(i)
      slack = 1.0e-9_dp*h*max(p0, p1) + 64*epsilon(1.0_dp)*abs(t%energy(i + 1))
      if (abs(w_rise - w_int) > t%rel_tol*h*max(p0, p1) + slack) then
         call bad(error, path, where//"nodes "//int_str(i)//", "//int_str(i + 1)// &
            & ": energy rise "//format_real(w_rise)//" is not the integral "// &
            & format_real(w_int)//" of the force between the nodes (forces "// &
            & format_real(p0)//", "//format_real(p1)//" over "//format_real(h)//")")
      end if
   end subroutine check_energy_integral

   !> The metadata of a table: finite, rel_tol in (0, 0.1], P_ref > 0, errors and
   !> R1 + R2 >= 0.
   subroutine check_meta(path, where, t, error)
      character(len=*), intent(in) :: path, where
      type(force_table), intent(in) :: t
      type(egw_error), allocatable, intent(out) :: error
      if (.not. (t%rel_tol > 0.0_dp .and. t%rel_tol <= 0.1_dp)) then
         call bad(error, path, where//"rel_tol = "//format_real(t%rel_tol)// &
            & ": must lie in (0, 0.1]")
      else if (.not. (ieee_is_finite(t%reference_force) .and. t%reference_force > 0)) then
         call bad(error, path, where//"reference_force = "// &
            & format_real(t%reference_force)//": must be finite and > 0")
      else if (.not. (ieee_is_finite(t%max_force_error) .and. t%max_force_error >= 0 &
         & .and. ieee_is_finite(t%max_stiffness_error) .and. t%max_stiffness_error >= 0)) &
         & then
         call bad(error, path, where//"max_force_error = "// &
            & format_real(t%max_force_error)//", max_stiffness_error = "// &
            & format_real(t%max_stiffness_error)//": must be finite and >= 0")
      else if (.not. (ieee_is_finite(t%radius_sum) .and. t%radius_sum >= 0)) then
         call bad(error, path, where//"radius_sum = "//format_real(t%radius_sum)// &
            & ": must be finite and >= 0 (0: not set)")
      end if
   end subroutine check_meta

end submodule egw_table_format_checks
