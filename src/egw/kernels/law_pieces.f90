!> The rough flat's ZMC loading law p(h) (egw_asperity's rough_flat_law with psi > 0)
!> tabulated once for many evaluations: ln p in Chebyshev series of one degree on equal
!> pieces of h, each series interpolating ln p at its piece's Chebyshev points (first
!> kind). p is entire in h (a Gaussian against a force of polynomial growth), so ln p is
!> analytic wherever p > 0 and the series converge geometrically: pieces of width 1 at
!> degree 24 meet the acceptance below from h = -40 to the underflow edge (psi 0.1 .. 30).
!> Evaluation (Clenshaw, ln p and d ln p/dh, one exp) costs ~1/10 of the integral.
!>
!> Acceptance (what the tabulation promises where it answers): on every piece, at the
!> piece's Chebyshev extrema (the points farthest from the interpolation nodes) and its
!> midpoints between them, |ln p_table - ln p| <= ln_tol (1 + |ln p|/64), i.e. p to a
!> relative 5e-13 near p ~ 1 and 6e-12 at the underflow edge (ln p ~ -700), and
!> |dp/dh_table - dp/dh| <= slope_tol |dp/dh|. These are the integral's own consistency,
!> not the series' error: at psi 1 the check finds 1.6e-14 (deep) to 2.3e-13 (h ~ 30) on
!> ln p (scaled as above) and 5e-12 .. 8e-11 on dp/dh at width 1, and the same or more
!> at widths 1/2 and 1/4 (the series interpolate the integral's last-bit noise, which
!> the derivative of a narrower piece magnifies). A piece that fails halves the width of
!> all of them (up to max_halvings); a law that still fails is not tabulated
!> (pieces%n = 0: every evaluation asks the exact law).
module egw_law_pieces
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use egw_kinds, only: dp, pi
   use egw_asperity, only: rough_flat_law
   implicit none
   private

   public :: zmc_law_pieces, law_pieces_at, unload_pieces_at, chebyshev_fit, clenshaw

   !> Degree of each piece's series.
   integer, parameter, public :: degree = 24
   !> Acceptance on ln p (absolute, scaled by 1 + |ln p|/64) and on dp/dh (relative).
   real(dp), parameter, public :: ln_tol = 5.0e-13_dp, slope_tol = 3.0e-10_dp
   !> Widths tried: 1, 1/2, ... 1/2^max_halvings.
   integer, parameter, public :: max_halvings = 4
   !> Below this p the law is left to the exact integral (ln p near ln(tiny) ~ -708 has
   !> few digits left and the series would carry p into subnormals).
   real(dp), parameter, public :: p_floor = 1.0e-280_dp

   !> The unloading law Z_u(Delta, h_min) of the same ZMC law at one closest approach
   !> h_min, tabulated in Delta = h - h_min >= 0 by egw_unloading's tabulate_unloading
   !> (the deep plastic zone of a rough + cap build, where every point's shifted h_min is
   !> the cap's one root h_y): ln Z_u in Chebyshev series of this module's degree on the
   !> pieces between edges(0:n), broken at unloading_kinks (where d^2 Z_u/dh^2 jumps).
   !> Answers h_min within slack of its own (rounding of the solver's shifted gaps; Z_u
   !> moves by |dZ_u/dh_min| slack, below 1e-10 relative, the acceptance's scale). From
   !> edges(n) + 1 on Z_u < p_floor (the build found it there, and Z_u decreases in
   !> Delta): answered as 0, as the integral's own Gaussian cut-off answers farther out
   !> (a pressure 1e-280 of the law's scale moves no sum of the solver). Empty (n = 0):
   !> the integral answers.
   type, public :: unload_pieces
      real(dp) :: h_min = 0.0_dp, slack = -1.0_dp
      integer :: n = 0
      real(dp), allocatable :: edges(:)   !< (0:n), ascending, edges(0) = 0
      real(dp), allocatable :: c(:, :)    !< (0:degree, n): ln Z_u's coefficients
      !> the largest |ln Z_u error|/(1 + |ln Z_u|/64) and dZ_u/dh relative error checked
      real(dp) :: ln_error = 0.0_dp, slope_error = 0.0_dp
   end type unload_pieces

   !> A tabulated ZMC loading law (see the module's notes). Empty (n = 0): not tabulated.
   type, public :: law_pieces
      real(dp) :: psi = 0.0_dp, hardness_coeff = 0.6_dp, plastic_ratio = 54.0_dp
      real(dp) :: h_lo = 0.0_dp, h_hi = 0.0_dp   !< the tabulated range [h_lo, h_hi)
      real(dp) :: width = 0.0_dp                 !< width of a piece
      integer :: n = 0                           !< number of pieces
      !> c(0:degree, k): Chebyshev coefficients of ln p on piece k, in x in [-1, 1]
      real(dp), allocatable :: c(:, :)
      !> the largest |ln p error|/(1 + |ln p|/64) and dp/dh relative error met at the check
      real(dp) :: ln_error = 0.0_dp, slope_error = 0.0_dp
      !> the same law's unloading at one h_min (empty unless a build added it)
      type(unload_pieces) :: unload
   end type law_pieces

contains

   !> The ZMC loading law of (psi, K, rho_p) tabulated on [h_lo, h_edge), h_edge the first
   !> integer h >= 0 with p(h) < 1e-280 (~37); h_lo (default -40) <= -1. psi <= 0, an
   !> h_lo out of range or a law that fails the acceptance: the empty table.
   pure function zmc_law_pieces(psi, hardness_coeff, plastic_ratio, h_lo) result(t)
      real(dp), intent(in) :: psi             !< plasticity index (> 0)
      real(dp), intent(in) :: hardness_coeff  !< ZMC K
      real(dp), intent(in) :: plastic_ratio   !< ZMC rho_p
      real(dp), intent(in), optional :: h_lo  !< low end of the range (<= -1)
      type(law_pieces) :: t
      real(dp) :: lo, hi, p(1), dpdh(1), w
      integer :: halving
      logical :: ok

      t%psi = psi
      t%hardness_coeff = hardness_coeff
      t%plastic_ratio = plastic_ratio
      lo = -40.0_dp
      if (present(h_lo)) lo = h_lo
      if (.not. (psi > 0.0_dp .and. ieee_is_finite(psi) .and. lo <= -1.0_dp .and. &
         & lo >= -1.0e6_dp)) return
      lo = real(floor(lo), dp)
      hi = 0.0_dp
      do
         call rough_flat_law([hi], psi, hardness_coeff, plastic_ratio, p, dpdh)
         if (.not. p(1) >= p_floor .or. hi > 1.0e3_dp) exit
         hi = hi + 1.0_dp
      end do
      ! [lo, hi - 1]: the last whole piece ends where p >= p_floor still
      hi = hi - 1.0_dp
      if (.not. hi > lo) return
      w = 1.0_dp
      do halving = 0, max_halvings
         call tabulate(t, lo, hi, w, ok)
         if (ok) return
         w = 0.5_dp*w
      end do
      t%n = 0
      if (allocated(t%c)) deallocate (t%c)
   end function zmc_law_pieces

   !> t's pieces of width w on [lo, hi) and their check; ok when every piece passes.
   pure subroutine tabulate(t, lo, hi, w, ok)
      type(law_pieces), intent(inout) :: t
      real(dp), intent(in) :: lo, hi, w
      logical, intent(out) :: ok
      integer, parameter :: m = degree + 1
      real(dp) :: x(m), cosines(0:degree, m), h(m), p(m), dpdh(m), lnp(m)
      real(dp) :: xc(2*m - 1), hc(2*m - 1), pc(2*m - 1), dc(2*m - 1), lt, dlt, err
      integer :: j, k, i

      t%h_lo = lo
      t%width = w
      t%n = nint((hi - lo)/w)
      t%h_hi = lo + t%n*w
      t%ln_error = 0.0_dp
      t%slope_error = 0.0_dp
      if (allocated(t%c)) deallocate (t%c)
      allocate (t%c(0:degree, t%n))
      do j = 1, m
         x(j) = cos(pi*(real(j, dp) - 0.5_dp)/m)
         do k = 0, degree
            cosines(k, j) = cos(pi*k*(real(j, dp) - 0.5_dp)/m)
         end do
      end do
      ! check points: the extrema of T_m, cos(pi i/m), and the midpoints between them
      do i = 1, 2*m - 1
         xc(i) = cos(0.5_dp*pi*real(i, dp)/m)
      end do
      ok = .true.
      do i = 1, t%n
         h = piece_h(t, i, x)
         call rough_flat_law(h, t%psi, t%hardness_coeff, t%plastic_ratio, p, dpdh)
         if (.not. all(p > 0.0_dp .and. ieee_is_finite(p))) then
            ok = .false.
            return
         end if
         lnp = log(p)
         do k = 0, degree
            t%c(k, i) = (2.0_dp/m)*sum(lnp*cosines(k, :))
         end do
         t%c(0, i) = 0.5_dp*t%c(0, i)
         hc = piece_h(t, i, xc)
         call rough_flat_law(hc, t%psi, t%hardness_coeff, t%plastic_ratio, pc, dc)
         do j = 1, size(xc)
            call clenshaw(t%c(:, i), xc(j), 2.0_dp/w, lt, dlt)
            if (.not. pc(j) > 0.0_dp) then
               ok = .false.
               return
            end if
            err = abs(lt - log(pc(j)))/(1.0_dp + abs(log(pc(j)))/64.0_dp)
            t%ln_error = max(t%ln_error, err)
            ! dp/dh from the table, exp(lt) dlt, against the law's
            err = abs(exp(lt)*dlt - dc(j))/abs(dc(j))
            t%slope_error = max(t%slope_error, err)
         end do
         if (.not. (t%ln_error <= ln_tol .and. t%slope_error <= slope_tol)) then
            ok = .false.
            return
         end if
      end do
   end subroutine tabulate

   !> The h of piece i at its local coordinates x in [-1, 1].
   pure function piece_h(t, i, x) result(h)
      type(law_pieces), intent(in) :: t
      integer, intent(in) :: i
      real(dp), intent(in) :: x(:)
      real(dp) :: h(size(x))
      h = t%h_lo + t%width*(real(i - 1, dp) + 0.5_dp*(x + 1.0_dp))
   end function piece_h

   !> sum c_k T_k(x) and its derivative in h (dxdh = dx/dh), Clenshaw's recurrences.
   pure subroutine clenshaw(c, x, dxdh, s, ds)
      real(dp), intent(in) :: c(0:)   !< the coefficients c_0 .. c_degree
      real(dp), intent(in) :: x       !< the local coordinate in [-1, 1]
      real(dp), intent(in) :: dxdh    !< dx/dh of the piece
      real(dp), intent(out) :: s      !< the series' value
      real(dp), intent(out) :: ds     !< its derivative in h
      real(dp) :: b0, b1, b2, d0, d1, d2, x2
      integer :: k
      x2 = 2.0_dp*x
      b1 = 0.0_dp
      b2 = 0.0_dp
      d1 = 0.0_dp
      d2 = 0.0_dp
      do k = ubound(c, 1), 1, -1
         ! b_k = c_k + 2x b_{k+1} - b_{k+2}; d_k = 2 b_{k+1} + 2x d_{k+1} - d_{k+2}
         b0 = c(k) + x2*b1 - b2
         d0 = 2.0_dp*b1 + x2*d1 - d2
         b2 = b1
         b1 = b0
         d2 = d1
         d1 = d0
      end do
      s = c(0) + x*b1 - b2
      ds = (b1 + x*d1 - d2)*dxdh
   end subroutine clenshaw

   !> The Chebyshev coefficients c(0:degree) of the series interpolating v at the points
   !> x_j = cos(pi (j - 1/2)/(degree + 1)), j = 1 .. degree + 1 (chebyshev_fit's nodes:
   !> pass x to get them).
   pure subroutine chebyshev_fit(v, c, x)
      real(dp), intent(in), optional :: v(degree + 1)   !< the values at the nodes
      real(dp), intent(out), optional :: c(0:degree)    !< their series' coefficients
      real(dp), intent(out), optional :: x(degree + 1)  !< the nodes
      integer, parameter :: m = degree + 1
      integer :: j, k
      if (present(x)) then
         do j = 1, m
            x(j) = cos(pi*(real(j, dp) - 0.5_dp)/m)
         end do
      end if
      if (.not. (present(v) .and. present(c))) return
      do k = 0, degree
         c(k) = 0.0_dp
         do j = 1, m
            c(k) = c(k) + v(j)*cos(pi*k*(real(j, dp) - 0.5_dp)/m)
         end do
         c(k) = (2.0_dp/m)*c(k)
      end do
      c(0) = 0.5_dp*c(0)
   end subroutine chebyshev_fit

   !> Z_u and dZ_u/dh (at fixed h_min) of a tabulated unloading law at Delta = h - h_min
   !> for a closest approach h_min (0 from edges(n) + 1 on); inside false (p, dpdh
   !> untouched) where h_min is not the table's (beyond its slack), Delta in [edges(n),
   !> edges(n) + 1), below 0 or NaN, or the table empty.
   elemental subroutine unload_pieces_at(t, delta, h_min, p, dpdh, inside)
      type(unload_pieces), intent(in) :: t   !< from egw_unloading's tabulate_unloading
      real(dp), intent(in) :: delta, h_min   !< h - h_min and h_min, / sigma
      real(dp), intent(inout) :: p, dpdh     !< Z_u and dZ_u/dh
      logical, intent(out) :: inside         !< answered from the table
      real(dp) :: x, lnp, dlnp
      integer :: lo, hi, mid
      inside = .false.
      if (t%n == 0) return
      if (.not. abs(h_min - t%h_min) <= t%slack) return
      if (delta >= t%edges(t%n) + 1.0_dp) then
         ! (~1 M of the psi 1 build's 3.8 M calls: there the integral found t* and then
         ! ~5 % of them integrated a Z_u below 1e-280)
         p = 0.0_dp
         dpdh = 0.0_dp
         inside = .true.
         return
      end if
      if (.not. (delta >= t%edges(0) .and. delta < t%edges(t%n))) return
      lo = 0
      hi = t%n
      do while (hi - lo > 1)
         mid = (lo + hi)/2
         if (delta < t%edges(mid)) then
            hi = mid
         else
            lo = mid
         end if
      end do
      ! piece hi spans [edges(lo), edges(hi))
      x = (2.0_dp*delta - (t%edges(lo) + t%edges(hi)))/(t%edges(hi) - t%edges(lo))
      call clenshaw(t%c(:, hi), x, 2.0_dp/(t%edges(hi) - t%edges(lo)), lnp, dlnp)
      p = exp(lnp)
      dpdh = p*dlnp
      inside = .true.
   end subroutine unload_pieces_at

   !> p and dp/dh of the tabulated law at h (unscaled, as rough_flat_law); inside false
   !> (p, dpdh untouched) where h is outside the table's range, NaN, or the table empty.
   elemental subroutine law_pieces_at(t, h, p, dpdh, inside)
      type(law_pieces), intent(in) :: t   !< from zmc_law_pieces
      real(dp), intent(in) :: h           !< separation / sigma
      real(dp), intent(inout) :: p, dpdh  !< the law's p and dp/dh
      logical, intent(out) :: inside      !< h within [h_lo, h_hi) of a tabulated law
      real(dp) :: s, x, lnp, dlnp
      integer :: i
      inside = .false.
      if (.not. (h >= t%h_lo .and. h < t%h_hi)) return
      s = (h - t%h_lo)/t%width
      i = min(int(s), t%n - 1)
      x = 2.0_dp*(s - i) - 1.0_dp
      call clenshaw(t%c(:, i + 1), x, 2.0_dp/t%width, lnp, dlnp)
      p = exp(lnp)
      dpdh = p*dlnp
      inside = .true.
   end subroutine law_pieces_at

end module egw_law_pieces
