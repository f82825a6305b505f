!> Rough-flat laws as objects: the mean pressure p of a rough flat pressed onto a smooth
!> rigid flat against their mean separation u, and dp/du. The sphere solver takes any
!> `flat_law` (doc/theory.md §11); it asks for p(u) and dp/du and never how they were made.
!>
!> Sign conventions: u > 0 apart (u is measured from the law's reference plane: the mean
!> plane of the heights for a tabulated, Persson or BEM law, the summit base plane for GW's);
!> p >= 0 compressive; dp/du <= 0. Units are the caller's (any consistent set) except in
!> `gw_flat_law` and `scaled_flat_law`, which are in the solver's scaled units (lengths in
!> sigma, pressures in E sqrt(sigma/R)).
module egw_flat_law
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan, ieee_value, &
      & ieee_quiet_nan
   use egw_kinds, only: dp
   use egw_search, only: bracket_interval
   use egw_status, only: egw_error, egw_invalid_argument, fatal_error, format_real, int_str
   use egw_asperity, only: rough_flat_law
   implicit none
   private

   !> A rough-flat law p(u).
   !> (No data components here: gfortran 12 lays out an abstract parent's components
   !> differently across modules, so each law keeps its own and answers length/modulus.)
   type, abstract, public :: flat_law
   contains
      !> p and dp/du at the separations u (arrays of one size).
      procedure(law_pressure), deferred :: pressure
      !> The same law in other units: u' = u/unit_length, p' = p/pressure_unit.
      procedure(law_rescaled), deferred :: rescaled
      !> Natural length of the law, the sphere solver's unit of separation: the surface's
      !> rms height where known, else the decay length -1/(d ln p/du) at the law's
      !> low-pressure end.
      procedure(law_number), deferred :: length
      !> E* the law was computed with (0: not known, e.g. a user's table).
      procedure(law_number), deferred :: modulus
   end type flat_law

   abstract interface
      pure subroutine law_pressure(law, u, p, dpdu)
         import :: flat_law, dp
         class(flat_law), intent(in) :: law
         real(dp), intent(in) :: u(:)        !< mean separations
         real(dp), intent(out) :: p(:)       !< mean pressures (>= 0)
         real(dp), intent(out) :: dpdu(:)    !< dp/du (<= 0)
      end subroutine law_pressure
      subroutine law_rescaled(law, unit_length, pressure_unit, scaled)
         import :: flat_law, dp
         class(flat_law), intent(in) :: law
         real(dp), intent(in) :: unit_length, pressure_unit   !< > 0
         class(flat_law), allocatable, intent(out) :: scaled
      end subroutine law_rescaled
      pure real(dp) function law_number(law)
         import :: flat_law, dp
         class(flat_law), intent(in) :: law
      end function law_number
   end interface

   !> GW's law of independent summits in scaled units (paper eqs. 9, 44): h = d/sigma from
   !> the summit base plane, p = scale f(h) with scale = mu/(2 sqrt 2) and f = F_{3/2}
   !> (elastic summits, psi = 0) or the ZMC integral (psi > 0): egw_asperity's
   !> rough_flat_law.
   type, extends(flat_law), public :: gw_flat_law
      real(dp) :: scale = 0.0_dp
      real(dp) :: psi = 0.0_dp, hardness_coeff = 0.6_dp, plastic_ratio = 54.0_dp
   contains
      procedure :: pressure => gw_pressure
      procedure :: rescaled => gw_rescaled
      procedure :: length => gw_length
      procedure :: modulus => gw_modulus
   end type gw_flat_law

   !> A tabulated law: nodes (u_i, p_i), u ascending and p strictly decreasing and > 0,
   !> interpolated by a monotone cubic Hermite in (u, ln p) (C1; exact at the nodes; slopes
   !> from dp/du where given, scaled back where they exceed Fritsch and Carlson's bound
   !> (alpha^2 + beta^2 <= 9 per interval), else Fritsch-Carlson's), and continued beyond
   !> both ends by the end nodes' exponentials ln p linear in u (the large-separation asymptote of
   !> Persson's theory and of BEM, p ~ exp(-u/u0), at the far end; a stiff, finite
   !> continuation at the near end). Optional contact-area fraction, linear between nodes.
   type, extends(flat_law), public :: table_flat_law
      real(dp), allocatable :: u(:), lnp(:), slope(:)  !< nodes, ln p, d ln p/du
      real(dp), allocatable :: area(:)                 !< contact-area fraction (or none)
      real(dp) :: natural_length = 0.0_dp   !< see flat_law%length
      real(dp) :: law_modulus = 0.0_dp      !< see flat_law%modulus
   contains
      procedure :: pressure => table_pressure
      procedure :: rescaled => table_rescaled
      procedure :: length => table_length
      procedure :: modulus => table_modulus
      procedure :: contact_area => table_contact_area
   end type table_flat_law

   public :: new_table_law

contains

   pure subroutine gw_pressure(law, u, p, dpdu)
      class(gw_flat_law), intent(in) :: law
      real(dp), intent(in) :: u(:)
      real(dp), intent(out) :: p(:), dpdu(:)
      call rough_flat_law(u, law%psi, law%hardness_coeff, law%plastic_ratio, p, dpdu)
      p = law%scale*p
      dpdu = law%scale*dpdu
   end subroutine gw_pressure

   !> GW's law is already scaled: only a unit of pressure (or of length 1) is meaningful.
   subroutine gw_rescaled(law, unit_length, pressure_unit, scaled)
      class(gw_flat_law), intent(in) :: law
      real(dp), intent(in) :: unit_length, pressure_unit
      class(flat_law), allocatable, intent(out) :: scaled
      type(gw_flat_law) :: g
      ! (a unit of length other than 1 would change f's argument: not a GW law any more;
      ! the solver never asks for one)
      g = law
      g%scale = law%scale/pressure_unit
      allocate (scaled, source=g)
   end subroutine gw_rescaled

   !> GW's law is in units of sigma: length 1; its E* is the solver's unit.
   pure real(dp) function gw_length(law)
      class(gw_flat_law), intent(in) :: law
      gw_length = 1.0_dp
   end function gw_length

   pure real(dp) function gw_modulus(law)
      class(gw_flat_law), intent(in) :: law
      gw_modulus = 0.0_dp
   end function gw_modulus

   pure real(dp) function table_length(law)
      class(table_flat_law), intent(in) :: law
      table_length = law%natural_length
   end function table_length

   pure real(dp) function table_modulus(law)
      class(table_flat_law), intent(in) :: law
      table_modulus = law%law_modulus
   end function table_modulus

   subroutine table_rescaled(law, unit_length, pressure_unit, scaled)
      class(table_flat_law), intent(in) :: law
      real(dp), intent(in) :: unit_length, pressure_unit
      class(flat_law), allocatable, intent(out) :: scaled
      type(table_flat_law) :: t
      t%u = law%u/unit_length
      t%lnp = law%lnp - log(pressure_unit)
      t%slope = law%slope*unit_length
      if (allocated(law%area)) t%area = law%area
      t%natural_length = law%natural_length/unit_length
      t%law_modulus = law%law_modulus/pressure_unit
      allocate (scaled, source=t)
   end subroutine table_rescaled

   !> A tabulated law from nodes (u, p) and, optionally, dp/du at them (exact slopes, e.g.
   !> from a BEM's incremental stiffness), the contact-area fraction, the surface's rms
   !> height (the law's natural length) and the E* it was computed with. Errors
   !> (egw_invalid_argument, naming the node): fewer than 2 nodes, sizes that differ, u
   !> not finite or not strictly ascending, p not finite, not > 0 or not strictly
   !> decreasing, dp/du not finite or > 0, area outside [0, 1], length or modulus < 0.
   pure subroutine new_table_law(u, p, law, error, dpdu, area, length, modulus)
      real(dp), intent(in) :: u(:)   !< mean separations, ascending
      real(dp), intent(in) :: p(:)   !< mean pressures, > 0 and decreasing
      type(table_flat_law), intent(out) :: law   !< the tabulated law
      !> egw_invalid_argument naming the node, as above
      type(egw_error), allocatable, intent(out) :: error
      real(dp), intent(in), optional :: dpdu(:)   !< dp/du at the nodes (<= 0)
      real(dp), intent(in), optional :: area(:)   !< contact-area fraction at the nodes
      real(dp), intent(in), optional :: length    !< rms height (0: from the table)
      real(dp), intent(in), optional :: modulus   !< E* of the law (0: not known)
      integer :: n, i
      real(dp), allocatable :: secant(:)
      real(dp) :: alpha, beta, tau

      n = size(u)
      call check_table(u, p, error, dpdu, area)
      if (allocated(error)) return
      if (present(length)) then
         if (.not. (ieee_is_finite(length) .and. length >= 0.0_dp)) then
            call fatal_error(error, egw_invalid_argument, "length = "//format_real(length) &
               & //": the law's length must be finite and >= 0 (0: from the table)")
            return
         end if
         law%natural_length = length
      end if
      if (present(modulus)) then
         if (.not. (ieee_is_finite(modulus) .and. modulus >= 0.0_dp)) then
            call fatal_error(error, egw_invalid_argument, "modulus = "//format_real(modulus) &
               & //": the law's modulus must be finite and >= 0 (0: not known)")
            return
         end if
         law%law_modulus = modulus
      end if
      law%u = u
      law%lnp = log(p)
      allocate (secant(n - 1), law%slope(n))
      secant = (law%lnp(2:) - law%lnp(:n - 1))/(u(2:) - u(:n - 1))
      if (.not. all(ieee_is_finite(secant))) then
         i = findloc(ieee_is_finite(secant), .false., dim=1)
         call fatal_error(error, egw_invalid_argument, "u("//int_str(i + 1)//") = " &
            & //format_real(u(i + 1))//": too close to u("//int_str(i)//") = " &
            & //format_real(u(i))//" for the change of ln p between them (not finite)")
         return
      end if
      if (present(dpdu)) then
         law%slope = dpdu/p
         if (.not. all(ieee_is_finite(law%slope))) then
            i = findloc(ieee_is_finite(law%slope), .false., dim=1)
            call fatal_error(error, egw_invalid_argument, "dpdu("//int_str(i)//") = " &
               & //format_real(dpdu(i))//": d ln p/du = dpdu/p is not finite there")
            return
         end if
         ! Fritsch-Carlson's limit: where a given slope is over 3x its interval's secant
         ! (ln p strongly curved between coarse nodes, as near a BEM law's full contact),
         ! both ends of the interval are scaled back so that the cubic stays monotone
         do i = 1, n - 1
            alpha = law%slope(i)/secant(i)
            beta = law%slope(i + 1)/secant(i)
            if (alpha**2 + beta**2 > 9.0_dp) then
               tau = 3.0_dp/sqrt(alpha**2 + beta**2)
               law%slope(i) = tau*alpha*secant(i)
               law%slope(i + 1) = tau*beta*secant(i)
            end if
         end do
      else
         ! Fritsch-Carlson: the harmonic mean of the neighbouring secants (all < 0), the
         ! end secants at the ends: a monotone interpolant.
         law%slope(1) = secant(1)
         law%slope(n) = secant(n - 1)
         do i = 2, n - 1
            law%slope(i) = 2.0_dp*secant(i - 1)*secant(i)/(secant(i - 1) + secant(i))
         end do
      end if
      if (present(area)) law%area = area
      if (law%natural_length == 0.0_dp) law%natural_length = -1.0_dp/law%slope(n)
      if (.not. (law%natural_length > 0.0_dp .and. ieee_is_finite(law%natural_length))) then
         call fatal_error(error, egw_invalid_argument, "p("//int_str(n)//") = " &
            & //format_real(p(n))//": the law's decay length at its low-pressure end is " &
            & //"not a positive number; give the length (the surface's rms height)")
      end if
   end subroutine new_table_law

   pure subroutine check_table(u, p, error, dpdu, area)
      real(dp), intent(in) :: u(:), p(:)
      type(egw_error), allocatable, intent(out) :: error
      real(dp), intent(in), optional :: dpdu(:), area(:)
      integer :: i, n
      n = size(u)
      if (n < 2 .or. size(p) /= n) then
         call fatal_error(error, egw_invalid_argument, "n = "//int_str(n)//", size(p) = " &
            & //int_str(size(p))//": a tabulated flat law needs n >= 2 nodes (u, p)")
         return
      end if
      if (present(dpdu)) then
         if (size(dpdu) /= n) then
            call fatal_error(error, egw_invalid_argument, "size(dpdu) = "// &
               & int_str(size(dpdu))//": must equal n = "//int_str(n))
            return
         end if
      end if
      if (present(area)) then
         if (size(area) /= n) then
            call fatal_error(error, egw_invalid_argument, "size(area) = "// &
               & int_str(size(area))//": must equal n = "//int_str(n))
            return
         end if
      end if
      do i = 1, n
         if (.not. ieee_is_finite(u(i)) .or. (i > 1 .and. .not. u(i) > u(max(i - 1, 1)))) &
            & then
            call fatal_error(error, egw_invalid_argument, "u("//int_str(i)//") = " &
               & //format_real(u(i))//": separations must be finite and strictly ascending")
            return
         end if
         if (.not. (ieee_is_finite(p(i)) .and. p(i) > 0.0_dp .and. log(p(i)) > -huge(1.0_dp)) &
            & .or. (i > 1 .and. .not. p(i) < p(max(i - 1, 1)))) then
            call fatal_error(error, egw_invalid_argument, "p("//int_str(i)//") = " &
               & //format_real(p(i))//": pressures must be finite, > 0 and strictly " &
               & //"decreasing as the separation grows")
            return
         end if
         if (present(dpdu)) then
            if (.not. (ieee_is_finite(dpdu(i)) .and. dpdu(i) <= 0.0_dp)) then
               call fatal_error(error, egw_invalid_argument, "dpdu("//int_str(i)//") = " &
                  & //format_real(dpdu(i))//": dp/du must be finite and <= 0")
               return
            end if
         end if
         if (present(area)) then
            if (.not. (area(i) >= 0.0_dp .and. area(i) <= 1.0_dp)) then
               call fatal_error(error, egw_invalid_argument, "area("//int_str(i)//") = " &
                  & //format_real(area(i))//": a contact-area fraction is in [0, 1]")
               return
            end if
         end if
      end do
   end subroutine check_table

   !> The interval of x in the nodes (0 below the first, n beyond the last).
   pure integer function interval(nodes, x) result(k)
      real(dp), intent(in) :: nodes(:), x
      if (x < nodes(1)) then
         k = 0
      else if (x >= nodes(size(nodes))) then
         k = size(nodes)
      else
         k = bracket_interval(nodes, x)
      end if
   end function interval

   pure subroutine table_pressure(law, u, p, dpdu)
      class(table_flat_law), intent(in) :: law
      real(dp), intent(in) :: u(:)
      real(dp), intent(out) :: p(:), dpdu(:)
      integer :: i, k, n
      real(dp) :: h, t, lnp, dlnp, h00, h10, h01, h11
      n = size(law%u)
      do i = 1, size(u)
         if (ieee_is_nan(u(i))) then
            p(i) = u(i)
            dpdu(i) = u(i)
            cycle
         end if
         k = interval(law%u, u(i))
         if (k == 0 .or. k == n) then
            if (k == 0) k = 1
            dlnp = law%slope(k)
            lnp = law%lnp(k) + dlnp*(u(i) - law%u(k))
         else
            h = law%u(k + 1) - law%u(k)
            t = (u(i) - law%u(k))/h
            h00 = (1.0_dp + 2.0_dp*t)*(1.0_dp - t)**2
            h10 = t*(1.0_dp - t)**2
            h01 = t*t*(3.0_dp - 2.0_dp*t)
            h11 = t*t*(t - 1.0_dp)
            lnp = h00*law%lnp(k) + h*h10*law%slope(k) + h01*law%lnp(k + 1) &
               & + h*h11*law%slope(k + 1)
            dlnp = 6.0_dp*t*(t - 1.0_dp)/h*(law%lnp(k) - law%lnp(k + 1)) &
               & + (1.0_dp - t)*(1.0_dp - 3.0_dp*t)*law%slope(k) &
               & + t*(3.0_dp*t - 2.0_dp)*law%slope(k + 1)
         end if
         ! ln p beyond the doubles: p = 0 (far) or the largest double (deep), and dp/du no
         ! steeper than the largest double.
         p(i) = exp(min(lnp, log(huge(1.0_dp))))
         dpdu(i) = -min(p(i)*abs(dlnp), huge(1.0_dp))
      end do
   end subroutine table_pressure

   !> Contact-area fraction at u (linear between nodes, the end values beyond the
   !> ends, 0 where the law had none at the far end); NaN when the law has no area data.
   elemental real(dp) function table_contact_area(law, u) result(a)
      class(table_flat_law), intent(in) :: law
      real(dp), intent(in) :: u
      integer :: k, n
      real(dp) :: t
      if (.not. allocated(law%area) .or. ieee_is_nan(u)) then
         a = ieee_value(1.0_dp, ieee_quiet_nan)
         return
      end if
      n = size(law%u)
      k = interval(law%u, u)
      if (k == 0) then
         a = law%area(1)
      else if (k == n) then
         a = law%area(n)
      else
         t = (u - law%u(k))/(law%u(k + 1) - law%u(k))
         a = (1.0_dp - t)*law%area(k) + t*law%area(k + 1)
      end if
   end function table_contact_area

end module egw_flat_law
