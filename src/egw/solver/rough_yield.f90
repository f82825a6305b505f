!> The first yield of a rough sphere under the flow-pressure cap (doc/theory.md §12): the
!> overlap m_y where the loading solve's largest total pressure first reaches p_y, and the
!> one threshold that says it has (cap_acts). The hysteresis build starts its turning
!> points there, the contact duration breaks its loading panels there (egw_impact).
module egw_rough_yield
   use egw_kinds, only: dp
   use egw_status, only: egw_error, format_real
   use egw_params, only: contact_params
   use egw_sphere_solver, only: solver_options
   use egw_rough_solve, only: solve_result
   use egw_rough_loading, only: solve_contact
   implicit none
   private

   public :: cap_acts, rough_first_yield

   !> A loading solve's largest pressure at or above this fraction of p_y counts as
   !> capped: the cap holds it at p_y up to the solve's rounding.
   real(dp), parameter :: capped_fraction = 1.0_dp - 1.0e-9_dp

contains

   !> Whether a loading solve with largest total pressure max_pressure has reached the
   !> flow pressure p_y (> 0; rounding aside: capped_fraction).
   elemental logical function cap_acts(max_pressure, flow_pressure)
      real(dp), intent(in) :: max_pressure   !< the solve's largest total pressure
      real(dp), intent(in) :: flow_pressure   !< p_y (0: no cap, never reached)
      cap_acts = flow_pressure > 0.0_dp .and. max_pressure >= capped_fraction*flow_pressure
   end function cap_acts

   !> The first yield m_y in [lo, hi] of a rough sphere with the cap, the cap known to act
   !> at hi: where the loading solve's largest total pressure reaches p_y (cap_acts), to
   !> tol [length]. Below m_y that pressure rises smoothly and concavely (~sqrt(delta) far
   !> from contact), so the secant through the two highest points below m_y approaches it
   !> from below in a few solves (bisection where the secant leaves the bracket or has no
   !> two points yet): on the E-GW + cap tables of the hysteresis suites 7-9 solves where
   !> bisection to the same tolerance took 24. The solves read only the peak pressure
   !> (stiffness=.false.: the same bits, no moved-mesh solve). lo if the cap acts there.
   subroutine rough_first_yield(params, options, lo, hi, tol, m_y, error)
      type(contact_params), intent(in) :: params   !< a rough model with the cap
      type(solver_options), intent(in) :: options   !< the loading solves' options
      real(dp), intent(in) :: lo, hi   !< the bracket [length]; the cap acts at hi
      real(dp), intent(in) :: tol   !< m_y to this [length]
      real(dp), intent(out) :: m_y   !< the first yield [length]
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      real(dp) :: a, b, x, x_a, g_a, x_b, g_b, g
      integer :: it, n_below
      a = lo
      b = hi
      m_y = lo
      call peak_gap(lo, g, error)
      if (allocated(error) .or. .not. g < 0.0_dp) return
      x_a = lo
      g_a = g
      x_b = lo
      g_b = g
      n_below = 1
      x = lo
      do it = 1, 40
         x = 0.5_dp*(a + b)
         if (n_below >= 2 .and. g_b > g_a) then
            x = x_b - g_b*(x_b - x_a)/(g_b - g_a)
            if (.not. (x > a .and. x < b)) x = 0.5_dp*(a + b)
            if (abs(x - x_b) <= tol) exit
         end if
         if (b - a <= tol) exit
         call peak_gap(x, g, error)
         if (allocated(error)) return
         if (.not. g < 0.0_dp) then
            b = x
         else
            a = x
            x_a = x_b
            g_a = g_b
            x_b = x
            g_b = g
            n_below = n_below + 1
         end if
      end do
      m_y = max(a, min(x, b))
   contains
      !> The loading solve's largest pressure at delta less the capped level (< 0: below
      !> first yield).
      subroutine peak_gap(delta, gap, error)
         real(dp), intent(in) :: delta
         real(dp), intent(out) :: gap
         type(egw_error), allocatable, intent(out) :: error
         type(solve_result) :: res
         gap = 0.0_dp
         call solve_contact(params, options, delta, res, error, stiffness=.false.)
         ! (the solve's message in its scaled units: which solve it was, in the user's)
         if (allocated(error)) error%message = "the capped loading solve at delta = "// &
            & format_real(delta)//": "//error%message
         if (allocated(error)) return
         if (cap_acts(res%max_pressure, params%flow_pressure)) return
         gap = res%max_pressure - capped_fraction*params%flow_pressure
      end subroutine peak_gap
   end subroutine rough_first_yield

end module egw_rough_yield
