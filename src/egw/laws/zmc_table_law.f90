!> GW's law with ZMC summits (psi > 0) tabulated once: the same law as egw_flat_law's
!> gw_flat_law (scaled units, p = scale f(h)) answered from egw_law_pieces' Chebyshev
!> pieces of ln f inside their range (f to a relative 5e-13, 6e-12 where f nears
!> underflow, and dp/dh to 3e-10: the pieces' acceptance) and from the exact integral
!> outside it. A solver that evaluates the law millions of times (a hysteresis build:
!> ~5 M calls at psi 1) builds it once and hands it to every problem; the integral costs
!> ~0.6 us a call, a piece ~1/10 of that.
module egw_zmc_table_law
   use egw_kinds, only: dp
   use egw_flat_law, only: flat_law
   use egw_asperity, only: rough_flat_law
   use egw_law_pieces, only: law_pieces, law_pieces_at
   implicit none
   private

   !> GW's ZMC law from pieces (scaled units, length 1, as gw_flat_law).
   type, extends(flat_law), public :: zmc_table_law
      real(dp) :: scale = 0.0_dp   !< mu/(2 sqrt 2), as gw_flat_law's
      type(law_pieces) :: pieces   !< the tabulated f (zmc_law_pieces)
   contains
      procedure :: pressure => zmc_table_pressure
      procedure :: rescaled => zmc_table_rescaled
      procedure :: length => zmc_table_length
      procedure :: modulus => zmc_table_modulus
   end type zmc_table_law

contains

   pure subroutine zmc_table_pressure(law, u, p, dpdu)
      class(zmc_table_law), intent(in) :: law
      real(dp), intent(in) :: u(:)
      real(dp), intent(out) :: p(:), dpdu(:)
      integer :: i
      logical :: inside
      do i = 1, size(u)
         call law_pieces_at(law%pieces, u(i), p(i), dpdu(i), inside)
         if (.not. inside) call rough_flat_law(u(i), law%pieces%psi, &
            & law%pieces%hardness_coeff, law%pieces%plastic_ratio, p(i), dpdu(i))
      end do
      p = law%scale*p
      dpdu = law%scale*dpdu
   end subroutine zmc_table_pressure

   !> As gw_flat_law's: only a unit of pressure is meaningful (the pieces are in h).
   subroutine zmc_table_rescaled(law, unit_length, pressure_unit, scaled)
      class(zmc_table_law), intent(in) :: law
      real(dp), intent(in) :: unit_length, pressure_unit
      class(flat_law), allocatable, intent(out) :: scaled
      type(zmc_table_law) :: g
      g%pieces = law%pieces
      g%scale = law%scale/pressure_unit
      allocate (scaled, source=g)
   end subroutine zmc_table_rescaled

   pure real(dp) function zmc_table_length(law)
      class(zmc_table_law), intent(in) :: law
      zmc_table_length = 1.0_dp
   end function zmc_table_length

   pure real(dp) function zmc_table_modulus(law)
      class(zmc_table_law), intent(in) :: law
      zmc_table_modulus = 0.0_dp
   end function zmc_table_modulus

end module egw_zmc_table_law
