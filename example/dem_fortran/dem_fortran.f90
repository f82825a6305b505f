!> DEM loop on an egw table: two glass beads (R1 = R2 = 1 mm, E = 70 GPa, nu = 0.22,
!> density 2500 kg/m^3) collide head-on at 0.2 m/s, velocity Verlet, SI units.
!> 1. Smooth (Hertz table): max overlap and contact time against the closed forms.
!> 2. Rough (E-GW, sigma = 0.1 um, mu = 4): elastic, so the coefficient of restitution
!>    is 1, and the max overlap is where the table's elastic energy equals the initial
!>    kinetic energy of the relative motion.
!> 3. Elasto-plastic (EP-GW, sigma = 0.5 um, mu = 4, psi = 1): the same loop on a hysteresis
!>    table (hysteresis_eval_state: the contact's state keeps its history and what the next
!>    step can reuse; hysteresis_eval with one real gives the same values, slower)
!>    dissipates energy; its
!>    restitution is printed next to the library's (restitution), agreeing to 1e-4 (the
!>    table's rel_tol 1e-4 of the force at the turning point bounds the energies to a few
!>    1e-5; the loop starts at the table's cut-off, below which no force acts).
!> Exits with status 1 if a check fails.
program dem_fortran
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error
   use egw_params, only: contact_params, model_hertz, model_egw
   use egw_rough_sphere, only: solver_options
   use egw_table, only: force_table, build_table, table_eval, table_energy
   use egw_hysteresis, only: hysteresis_table, build_hysteresis, hysteresis_eval_state, &
      & hysteresis_state_init, hysteresis_state_size
   use egw_impact, only: restitution, time_step
   use egw_params, only: model_epgw
   implicit none
   real(dp), parameter :: r1 = 1.0e-3_dp, e_young = 70.0e9_dp, nu = 0.22_dp, rho = 2500
   real(dp), parameter :: v0 = 0.2_dp                     ! relative approach speed [m/s]
   real(dp) :: mass, m_eff, delta_h, t_h, d_max, t_c, e_rest, d_energy, lo, hi
   type(contact_params) :: p
   type(force_table) :: table
   type(hysteresis_table) :: hyst
   type(egw_error), allocatable :: err
   real(dp) :: e_ref, w_diss
   logical :: ok = .true.

   mass = rho*4*pi*r1**3/3
   m_eff = mass/2                                         ! reduced mass m1 m2/(m1 + m2)
   p = contact_params(model=model_hertz, radius=r1/2, modulus=e_young/(2*(1 - nu**2)))
   call make_table(p, 2.0e-6_dp, table)
   call collide(table, 0.0_dp, d_max, t_c, e_rest)
   ! Hertz: (1/2) m v0^2 = (8/15) E sqrt(R) delta^(5/2); t_c = 2 (delta_h/v0) int_0^1
   ! (1 - x^(5/2))^(-1/2) dx, the integral = (2/5) B(2/5, 1/2).
   delta_h = (15*m_eff*v0**2/(16*p%modulus*sqrt(p%radius)))**0.4_dp
   t_h = 2*delta_h/v0*0.4_dp*gamma(0.4_dp)*sqrt(pi)/gamma(0.9_dp)
   write (*, '(a, 2es14.6)') "Hertz max overlap [m], closed form:", d_max, delta_h
   write (*, '(a, 2es14.6)') "Hertz contact time [s], closed form:", t_c, t_h
   ! Tolerances: the table's force error <= 1e-5 (rel_tol) moves the overlap by <= 0.4e-5
   ! (delta ~ energy^(2/5)); the time step t_c/5000 adds ~(pi/5000)^2 = 4e-7 (Verlet energy
   ! error, sampling of the maximum). Measured: ~1e-6.
   call check("Hertz max overlap", abs(d_max/delta_h - 1) < 1.0e-5_dp)
   call check("Hertz contact time", abs(t_c/t_h - 1) < 1.0e-5_dp)
   call check("Hertz restitution", abs(e_rest - 1) < 1.0e-5_dp)

   p%model = model_egw
   p%sigma = 0.1e-6_dp
   p%mu = 4
   call make_table(p, 2.0e-6_dp, table)
   call collide(table, table%cutoff, d_max, t_c, e_rest)
   lo = table%cutoff                                      ! bisection: energy(d) = KE
   hi = table%delta_max
   do while (hi - lo > 1.0e-12_dp*hi)
      d_energy = (lo + hi)/2
      if (table_energy(table, d_energy) < m_eff*v0**2/2) then
         lo = d_energy
      else
         hi = d_energy
      end if
   end do
   write (*, '(a, 2es14.6)') "E-GW max overlap [m], energy balance:", d_max, d_energy
   write (*, '(a, es14.6, a, f9.6)') "E-GW contact time [s]:", t_c, ", restitution:", e_rest
   ! the energy is the integral of the interpolated force: only the time step matters
   call check("E-GW max overlap", abs(d_max/d_energy - 1) < 1.0e-5_dp)
   call check("E-GW restitution", abs(e_rest - 1) < 1.0e-5_dp)
   ! the rough contact starts before the mean planes meet (delta < 0) and is softer
   call check("roughness softens the contact", d_max - table%cutoff > delta_h .and. t_c > t_h)

   p%model = model_epgw
   p%sigma = 0.5e-6_dp
   p%psi = 1
   call build_hysteresis(p, solver_options(), -3*p%sigma, 3*delta_h, 1.0e-4_dp, hyst, err)
   if (allocated(err)) then
      write (*, '(a)') "build_hysteresis failed: "//err%message
      error stop 1
   end if
   call impact(hyst, d_max, e_rest)
   call restitution(p, solver_options(), m_eff, v0, e_ref, w_diss, err)
   if (allocated(err)) then
      write (*, '(a)') "restitution failed: "//err%message
      error stop 1
   end if
   write (*, '(a, es14.6, a, 2f10.6)') "EP-GW max overlap [m]:", d_max, &
      & ", restitution (table loop, restitution):", e_rest, e_ref
   call check("EP-GW dissipates", e_rest < 1 - 1.0e-3_dp)
   call check("EP-GW restitution = restitution", abs(e_rest - e_ref) < 1.0e-4_dp)
   if (.not. ok) error stop 1
   write (*, '(a)') "dem_fortran: all checks passed"

contains

   subroutine make_table(p, delta_max, table)
      type(contact_params), intent(in) :: p
      real(dp), intent(in) :: delta_max
      type(force_table), intent(out) :: table
      type(egw_error), allocatable :: error
      call build_table(p, solver_options(), -10*p%sigma, delta_max, 1.0e-5_dp, table, error)
      if (allocated(error)) then
         write (*, '(a)') "build_table failed: "//error%message
         error stop 1
      end if
   end subroutine make_table

   !> Velocity Verlet for the relative coordinate of two equal spheres (overlap delta,
   !> reduced mass m_eff) from just outside the cut-off until they separate; the contact
   !> time is measured between the crossings of delta = d_touch (linear interpolation:
   !> exact where no force acts).
   subroutine collide(table, d_touch, d_max, t_contact, restitution)
      type(force_table), intent(in) :: table
      real(dp), intent(in) :: d_touch
      real(dp), intent(out) :: d_max, t_contact, restitution
      real(dp) :: d, v, f, k, dt, t, t_in, d_old
      d = min(table%cutoff, d_touch) - 1.0e-3_dp*delta_h_guess()
      v = v0                                              ! d(delta)/dt
      dt = (m_eff/(2*p%modulus*sqrt(p%radius*delta_h_guess())))**0.5_dp*pi/5000
      call table_eval(table, d, f, k)
      t = 0; t_in = -1; d_max = d
      do
         d_old = d
         v = v - dt/2*f/m_eff
         d = d + dt*v
         call table_eval(table, d, f, k)
         v = v - dt/2*f/m_eff
         t = t + dt
         if (d_old <= d_touch .and. d > d_touch) t_in = t - dt*(d - d_touch)/(d - d_old)
         d_max = max(d_max, d)
         if (t_in >= 0 .and. d <= d_touch) exit
      end do
      t_contact = t - dt*(d_touch - d)/(d_old - d) - t_in
      restitution = -v/v0
   end subroutine collide

   !> Velocity Verlet on a hysteresis table from the table's cut-off (the tail below it holds
   !> forces under 1e-12 of the reference: the approach from far apart changes nothing)
   !> until the spheres are back there, with the step of time_step for an error in e below
   !> 1e-5 (doc/theory.md 10): the history (largest overlap) starts at -huge (never loaded).
   subroutine impact(hyst, d_max, restitution)
      type(hysteresis_table), intent(in) :: hyst
      real(dp), intent(out) :: d_max, restitution
      real(dp) :: d, d0, d_old, v, f, k, dt, duration, state(hysteresis_state_size)
      type(egw_error), allocatable :: err
      integer :: stat
      call time_step(hyst%params, solver_options(), m_eff, v0, 1.0e-5_dp, duration, dt, err)
      if (allocated(err)) then
         write (*, '(a)') "time_step failed: "//err%message
         stop 1
      end if
      write (*, '(a,es13.6,a,es13.6)') "EP-GW contact duration [s]: ", duration, &
         & ", time step [s]: ", dt
      call hysteresis_state_init(state)   ! a new contact
      d0 = hyst%loading%cutoff
      d = d0
      v = v0
      call hysteresis_eval_state(hyst, d, state, f, k, stat)
      do
         d_old = d
         v = v - dt/2*f/m_eff
         d = d + dt*v
         call hysteresis_eval_state(hyst, d, state, f, k, stat)
         v = v - dt/2*f/m_eff
         if (d < d0 .and. d < d_old) exit
      end do
      restitution = -v/v0
      d_max = state(1)
   end subroutine impact

   !> Hertz overlap scale, only to choose the time step
   real(dp) function delta_h_guess()
      delta_h_guess = (15*m_eff*v0**2/(16*p%modulus*sqrt(p%radius)))**0.4_dp
   end function delta_h_guess

   subroutine check(what, passed)
      character(len=*), intent(in) :: what
      logical, intent(in) :: passed
      if (.not. passed) write (*, '(a)') "FAILED: "//what
      ok = ok .and. passed
   end subroutine check
end program dem_fortran
