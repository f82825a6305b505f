!> Contact profiles of a smooth sphere with the flow-pressure cap (doc/theory.md §12,
!> "Profiles with the cap"): the pressure p(r) and the surfaces' total normal displacement
!> w(r) of egw_cap_sphere's loading solve (cap_profile, on up to as many rings as asked)
!> and of its unloading from a loading history (cap_unload_profile), in the caller's units.
module egw_cap_profile
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error, fatal_error, format_real, egw_invalid_argument
   use egw_halfspace, only: radial_mesh, build_mesh, influence_row
   use egw_lapack, only: dgetrs
   use egw_ellip, only: ellipe_comp, ellipk_comp
   use egw_smooth_sphere, only: hertz_pressure, hertz_deflection
   use egw_cap_sphere, only: cap_options, cap_result, cap_history, cap_units, cap_unload, &
      & n_press, elastic_margin, fitted_load, check_inputs, gamma_start, load_fitted, &
      & u_plastic, keep_unloading, toward_one
   implicit none
   private

   public :: cap_profile, cap_unload_profile

contains

   !> Loading profile at delta (>= 0) of a sphere R, E* against the cap p_y: the contact
   !> pressure p(r) (<= p_y: p_y on the capped disc [0, c], the rings' pressures on the
   !> elastic annulus [c, a], 0 beyond a) and the surfaces' total normal displacement w(r)
   !> (elastic plus the plastic crater, so that the gap r**2/(2R) - delta + w is 0 on
   !> [0, a]: w = delta - r**2/(2R) there; beyond a the rings' elastic deflection). On
   !> the annulus p is interpolated between the ring midpoints (linear; p ~ sqrt(a - r)
   !> toward a and 1 - p ~ sqrt(r - c) toward c). Below delta_y (1 + elastic_margin):
   !> Hertz. options: the most rings (the finest level's n_rings 2**(n_levels - 1)).
   subroutine cap_profile(radius, modulus, flow_pressure, delta, options, r, pressure, &
      & deflection, error)
      real(dp), intent(in) :: radius, modulus, flow_pressure   !< R, E*, p_y
      real(dp), intent(in) :: delta                 !< overlap >= 0 [length]
      type(cap_options), intent(in) :: options      !< the rings
      real(dp), intent(in) :: r(:)                  !< radii >= 0 [length]
      real(dp), intent(out) :: pressure(:), deflection(:)   !< p, w at r
      type(egw_error), allocatable, intent(out) :: error   !< the solve's failure
      type(fitted_load) :: st
      real(dp), parameter :: thinnest_ring = 2.0e-11_dp
      real(dp) :: delta_y, a_y, force_y, dm, gamma, a
      integer :: i, m, m_max
      logical :: full
      call check_inputs(radius, modulus, flow_pressure, options, error)
      if (allocated(error)) return
      call cap_units(radius, modulus, flow_pressure, delta_y, a_y, force_y)
      dm = delta/delta_y
      if (.not. ieee_is_finite(delta) .or. .not. delta >= 0.0_dp .or. dm > 1.0e6_dp) then
         call fatal_error(error, egw_invalid_argument, "delta = "//format_real(delta) &
            & //": must be finite, >= 0 and at most 1e6 delta_y")
         return
      end if
      if (dm <= 1.0_dp + elastic_margin) then
         pressure = hertz_pressure(r, delta, radius, modulus)
         deflection = hertz_deflection(r, delta, radius)
         return
      end if
      ! the rings of the public solves first; then as many as asked while the thinnest
      ! ring, (1 - c/a)/m**2 of a, stays above thinnest_ring (below it, in the thin
      ! elastic edge beyond ~25 delta_y, the rings' pressures go wrong: -0.17 p_y at 30
      ! delta_y on 256 rings, where 64 give p in [0, p_y] and the force to 2e-10)
      m_max = options%n_rings*2**(options%n_levels - 1)
      m = min(m_max, 64)
      gamma = gamma_start(dm)
      call load_fitted(m, dm, options%max_active, gamma, st, full, error)
      if (allocated(error)) return
      if (.not. full .and. 2*m <= m_max .and. (1.0_dp - gamma)/real(2*m, dp)**2 >= &
         & thinnest_ring) then
         do while (2*m <= m_max .and. (1.0_dp - gamma)/real(2*m, dp)**2 >= thinnest_ring)
            m = 2*m
         end do
         call load_fitted(m, dm, options%max_active, gamma, st, full, error)
         if (allocated(error)) return
      end if
      if (full) then
         ! the fully capped limit (see t_cap): p = 1 on [0, a]
         a = -8.0_dp/pi**2 + sqrt(64.0_dp/pi**4 + 2.0_dp*dm)
         do i = 1, size(r)
            call full_profile(dm, a, r(i)/a_y, pressure(i), deflection(i))
         end do
      else
         do i = 1, size(r)
            call ring_profile(st, r(i)/a_y, pressure(i), deflection(i))
         end do
      end if
      pressure = flow_pressure*pressure
      deflection = delta_y*deflection
   end subroutine cap_profile

   !> Scaled p and w at rho of the fully capped limit at Delta, contact radius a: p = 1
   !> on [0, a]; w = Delta - rho**2/2 within, the uniform disc's (8 rho/pi**2) (E(a/rho)
   !> - (1 - a**2/rho**2) K(a/rho)) beyond.
   pure subroutine full_profile(delta, a, rho, p, w)
      real(dp), intent(in) :: delta, a, rho
      real(dp), intent(out) :: p, w
      real(dp) :: k, kc
      if (rho <= a) then
         p = 1.0_dp
         w = delta - 0.5_dp*rho**2
      else
         p = 0.0_dp
         k = a/rho
         kc = sqrt((1.0_dp - k)*(1.0_dp + k))
         w = 8.0_dp*rho/pi**2*(ellipe_comp(kc) - kc**2*ellipk_comp(kc))
      end if
   end subroutine full_profile

   !> Scaled p and w at rho of the loading solution st (see cap_profile).
   subroutine ring_profile(st, rho, p, w)
      type(fitted_load), intent(in) :: st
      real(dp), intent(in) :: rho
      real(dp), intent(out) :: p, w
      real(dp) :: x, t, row(st%mesh%n_elem*n_press), hr(st%mesh%n_elem)
      integer :: e, m, j
      m = st%m
      x = rho/st%a
      if (x <= 1.0_dp) then
         w = st%delta - 0.5_dp*rho**2
         if (x <= st%gamma) then
            p = 1.0_dp
         else if (x <= st%x(1)) then
            p = 1.0_dp - (1.0_dp - st%q(1))*sqrt((x - st%gamma)/(st%x(1) - st%gamma))
         else if (x >= st%x(m)) then
            p = st%q(m)*sqrt(max(0.0_dp, 1.0_dp - x)/(1.0_dp - st%x(m)))
         else
            j = 1
            do while (st%x(j + 1) < x)
               j = j + 1
            end do
            t = (x - st%x(j))/(st%x(j + 1) - st%x(j))
            p = (1.0_dp - t)*st%q(j) + t*st%q(j + 1)
         end if
      else
         p = 0.0_dp
         call influence_row(st%mesh, x, row)
         do e = 1, st%mesh%n_elem
            hr(e) = 2.0_dp/pi*sum(row((e - 1)*n_press + 1:e*n_press))
         end do
         w = st%a*(hr(1) + sum(hr(2:)*st%q))
      end if
   end subroutine ring_profile

   !> Unloading (or reloading) profile at delta <= delta_max after cap_load: the pressure
   !> p(r) of the elastic contact [0, b] of the deformed shape (the finest level's rings,
   !> interpolated between their midpoints: linear, flat toward 0, p ~ sqrt(b - r) toward
   !> b) and the surfaces' total normal displacement w(r): elastic plus the plastic crater
   !> u_pl, so that the gap r**2/(2R) - delta + w is 0 on [0, b] (w = delta - r**2/(2R)
   !> there) and beyond b w = the rings' elastic deflection + u_pl(r). At or below the
   !> residual overlap: p = 0, w = u_pl. Elastic history: Hertz at delta. The unloading
   !> rings are rebuilt at n_rings when that is more than history's (its force then
   !> differs from cap_unload's on history by the rings' error). Errors as cap_unload.
   subroutine cap_unload_profile(history, n_rings, delta, r, pressure, deflection, error)
      type(cap_history), intent(in) :: history   !< from cap_load
      !> the unloading rings (finest level), at least history's
      integer, intent(in) :: n_rings
      real(dp), intent(in) :: delta              !< overlap <= delta_max
      real(dp), intent(in) :: r(:)               !< radii >= 0 [length]
      real(dp), intent(out) :: pressure(:), deflection(:)   !< p, w at r
      type(egw_error), allocatable, intent(out) :: error   !< cap_unload's failure
      type(cap_result) :: res
      type(cap_history) :: hist
      type(radial_mesh) :: mesh
      real(dp), allocatable :: q(:, :), x(:), edges(:), row(:), hr(:)
      real(dp) :: d, b, rho, u, du, t, xr
      integer :: m, i, j, e, info
      hist = history
      if (.not. history%elastic .and. n_rings > history%n_unload(2)) then
         deallocate (hist%x_unload, hist%v_unload, hist%lu_unload, hist%piv_unload)
         call keep_unloading(hist, n_rings, error)
         if (allocated(error)) return
      end if
      call cap_unload(hist, delta, res, error)
      if (allocated(error)) return
      if (history%elastic) then
         pressure = hertz_pressure(r, delta, history%radius, history%modulus)
         deflection = hertz_deflection(r, delta, history%radius)
         return
      end if
      d = delta/hist%delta_y
      if (d <= hist%residual) then
         pressure = 0.0_dp
         do i = 1, size(r)
            call u_plastic(hist, r(i)/hist%a_y, u, du)
            deflection(i) = hist%delta_y*u
         end do
         return
      end if
      b = res%contact_radius/hist%a_y
      m = hist%n_unload(2)
      x = hist%x_unload(1:m, 2)
      allocate (q(m, 1))
      do i = 1, m
         call u_plastic(hist, b*x(i), u, du)
         q(i, 1) = (d - 0.5_dp*(b*x(i))**2 - u)/b
      end do
      call dgetrs('N', m, 1, hist%lu_unload, m, hist%piv_unload, q, m, info)
      edges = toward_one([(real(j, dp)/real(m, dp), j=0, m)])
      edges(1) = 0.0_dp
      edges(m + 1) = 1.0_dp
      call build_mesh(edges, 1, n_press, mesh)
      allocate (row(mesh%n_elem*n_press), hr(mesh%n_elem))
      do i = 1, size(r)
         rho = r(i)/hist%a_y
         xr = rho/b
         if (xr <= 1.0_dp) then
            deflection(i) = d - 0.5_dp*rho**2
            if (xr <= x(1)) then
               pressure(i) = q(1, 1)
            else if (xr >= x(m)) then
               pressure(i) = q(m, 1)*sqrt(max(0.0_dp, 1.0_dp - xr)/(1.0_dp - x(m)))
            else
               j = 1
               do while (x(j + 1) < xr)
                  j = j + 1
               end do
               t = (xr - x(j))/(x(j + 1) - x(j))
               pressure(i) = (1.0_dp - t)*q(j, 1) + t*q(j + 1, 1)
            end if
         else
            pressure(i) = 0.0_dp
            call influence_row(mesh, xr, row)
            do e = 1, mesh%n_elem
               hr(e) = 2.0_dp/pi*sum(row((e - 1)*n_press + 1:e*n_press))
            end do
            call u_plastic(hist, rho, u, du)
            deflection(i) = b*sum(hr*q(:, 1)) + u
         end if
      end do
      pressure = hist%flow_pressure*pressure
      deflection = hist%delta_y*deflection
   end subroutine cap_unload_profile

end module egw_cap_profile
