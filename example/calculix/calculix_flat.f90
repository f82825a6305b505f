!> Writes the pressure-overclosure curve of a rough flat for example/calculix: the GW
!> nominal pressure p_G (doc/theory.md section 3) of a steel surface on a rigid smooth one,
!> units mm, N, MPa: E* = 210000/(1 - 0.3^2) MPa, sigma = 1 um, summit radius
!> beta = 50 um, summit density eta = 500 /mm^2 (eta beta sigma = 0.025), linear
!> interpolation within rel_tol = 1e-3, overclosure up to +1 um: 133 pairs (CalculiX 2.20
!> uses at most 200 pairs of a tabular curve; the writer caps there), shifted so that
!> overclosure is measured from d_c, the separation where p_G has fallen to rel_tol p_G(0).
!> Usage: calculix-flat [output path]  (default flat.inc, included by block.inp)
program calculix_flat
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_params, only: contact_params, model_egw, mu_from_summits
   use egw_table_format, only: write_calculix_flat
   implicit none
   real(dp), parameter :: modulus = 210000/(1 - 0.3_dp**2), sigma = 1.0e-3_dp
   real(dp), parameter :: beta = 0.05_dp, eta = 500
   ! a flat has no radius; R only enters through mu = (8/3) eta sigma sqrt(2 R beta),
   ! and p_G depends on mu/sqrt(R) alone, so any R > 0 gives the same curve
   real(dp), parameter :: radius = 1
   type(contact_params) :: p
   type(egw_error), allocatable :: error
   character(len=256) :: path

   path = "flat.inc"
   if (command_argument_count() >= 1) call get_command_argument(1, path)
   p = contact_params(model=model_egw, radius=radius, modulus=modulus, sigma=sigma, &
      & mu=mu_from_summits(eta, beta, sigma, radius))
   ! shift: overclosure from d_c (CalculiX only reaches overclosure >= 0 in
   ! node-to-surface contact): the model's surfaces are the summit base planes at d_c
   call write_calculix_flat(p, 1.0e-3_dp, 1.0e-3_dp, trim(path), error, shift=.true.)
   if (allocated(error)) then
      write (*, '(a)') "calculix-flat: "//error%message
      error stop 1
   end if
   write (*, '(a)') "calculix-flat: wrote "//trim(path)
end program calculix_flat
