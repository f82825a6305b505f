!> The cap solver's start table (egw_cap_start, read by egw_cap_sphere's gamma_start): t = ln(c/(a - c)) of the
!> converged loading solve (load_fitted, 64 rings: cap_solve_options's finest level) at
!> Delta = 1 + exp(x), x from ln(1e-4) to ln(36) in steps of 0.05 (257 points; printed as
!> Fortran). Build as tools/bench/cap_local_error.f90 (its header), run without arguments.
program cap_gamma_start_table
   use egw_kinds, only: dp
   use egw_cap_sphere, only: load_fitted, fitted_load, gamma_start
   use egw_status, only: egw_error
   implicit none
   integer, parameter :: n = 257
   type(fitted_load) :: st
   type(egw_error), allocatable :: err
   real(dp) :: x, g, t(n)
   logical :: full
   integer :: i
   do i = 1, n
      x = log(1.0e-4_dp) + 0.05_dp*real(i - 1, dp)
      g = gamma_start(1.0_dp + exp(x))
      call load_fitted(64, 1.0_dp + exp(x), 60, g, st, full, err)
      if (allocated(err)) error stop "load_fitted failed"
      t(i) = log(g/(1.0_dp - g))
      if (full) t(i) = 18.0_dp
   end do
   print '(4(f13.9,"_dp,"))', t
end program cap_gamma_start_table
