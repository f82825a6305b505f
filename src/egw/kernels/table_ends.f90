!> The laws at the ends of a force table (doc/theory.md §9): the separated tail of a rough
!> sphere, the rigid-sphere law far apart, and the deep-overlap asymptote, the Hertz form
!> with the rough layer's offset. Closed forms matched to a table's end node; egw_table
!> and egw_table_universal continue their interpolants with them.
module egw_table_ends
   use egw_kinds, only: dp
   use egw_gauss, only: gauss_f32, gauss_f52
   implicit none
   private

   public :: tail_force, deep_force

contains

   !> The separated tail of a rough sphere below the cut-off delta_c (doc/theory.md §9).
   !> Far apart the sphere barely deforms, so the force is that of a rigid sphere on the
   !> rough flat, P = 2 pi R int_{-delta}^inf p_G(d) dd; with elastic Gaussian summits
   !> (p_G proportional to F_{3/2}(d/sigma)) this is
   !>   P = (2/5) pi sqrt(R/2) mu E* sigma^(3/2) F_{5/2}(-delta/sigma)
   !> (solves agree to 2e-5 at -4 sigma, 2e-7 at -5 sigma, 5e-10 at -6 sigma for mu = 4).
   !> Matched to the table's first node (p_c, k_c):
   !>   P = p_c F_{5/2}(h)/F_{5/2}(h_c) exp(kappa (delta - delta_c)),  h = -delta/sigma.
   !> Elastic summits: kappa = 0, the rigid-sphere law itself (its slope at delta_c meets
   !> k_c to the solver's accuracy). Plastic summits (EP-GW, psi > 0), many of which yield
   !> even far apart: kappa = k_c/p_c - (5/2) F_{3/2}(h_c)/(sigma F_{5/2}(h_c)) matches
   !> the slope too. C1 at delta_c, 0 as delta -> -inf.
   pure subroutine tail_force(delta_c, p_c, k_c, sigma, plastic, delta, force, stiffness)
      real(dp), intent(in) :: delta_c   !< cut-off, the table's first node [length]
      real(dp), intent(in) :: p_c, k_c  !< force and stiffness there
      real(dp), intent(in) :: sigma     !< summit height deviation [length], > 0
      logical, intent(in) :: plastic    !< summits yield (EP-GW with psi > 0)
      real(dp), intent(in) :: delta     !< overlap [length], < delta_c
      real(dp), intent(out) :: force, stiffness
      real(dp) :: f52, f52_c, kappa, log_p
      force = 0.0_dp
      stiffness = 0.0_dp
      f52_c = gauss_f52(-delta_c/sigma)
      f52 = gauss_f52(-delta/sigma)
      if (.not. (p_c > 0.0_dp .and. f52_c > 0.0_dp .and. f52 > 0.0_dp)) return
      kappa = 0.0_dp
      if (plastic) kappa = k_c/p_c - 2.5_dp*gauss_f32(-delta_c/sigma)/(sigma*f52_c)
      log_p = log(p_c) + log(f52/f52_c) + kappa*(delta - delta_c)
      if (.not. log_p > log(tiny(1.0_dp))) return
      force = exp(min(log_p, log(p_c)))
      stiffness = force*(2.5_dp*gauss_f32(-delta/sigma)/(sigma*f52) + kappa)
   end subroutine tail_force

   !> Deep overlaps above the last node d_e (force p_e, stiffness k_e): the Hertz form of
   !> the model's asymptote, P = c (delta - delta_0)^(3/2), with c and delta_0 (the rough
   !> layer's offset) fitted to p_e and k_e:
   !>   P = p_e r^(3/2),  K = k_e r^(1/2),  r = 1 + (delta - d_e)/u_0,  u_0 = 1.5 p_e/k_e,
   !> C1 and monotone; exact for Hertz (delta_0 = 0). Within 0.4 % of E-GW and EP-GW solves
   !> up to 0.2 R from delta_max = 20 sigma (doc/theory.md §9). Where p_e or k_e is not
   !> positive, the linear continuation.
   pure subroutine deep_force(d_e, p_e, k_e, delta, force, stiffness)
      real(dp), intent(in) :: d_e        !< last node [length]
      real(dp), intent(in) :: p_e, k_e   !< force and stiffness there
      real(dp), intent(in) :: delta      !< overlap [length], >= d_e
      real(dp), intent(out) :: force, stiffness
      real(dp) :: r
      if (p_e > 0.0_dp .and. k_e > 0.0_dp) then
         r = 1.0_dp + (delta - d_e)*k_e/(1.5_dp*p_e)
         stiffness = k_e*sqrt(r)
         force = p_e*r*sqrt(r)
      else
         stiffness = k_e
         force = p_e + k_e*(delta - d_e)
      end if
   end subroutine deep_force

end module egw_table_ends
