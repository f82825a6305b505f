! audit23: CPU time of read_table, read_universal, read_hysteresis on the files make_tables
! below writes (in one file: the programs make_tables and read_bench); link once against
! libegw.a and once with main's formats/table_format_checks.f90 compiled first (-J elsewhere).
program make_tables
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_params, only: contact_params, model_egw, model_epgw
   use egw_rough_sphere, only: solver_options
   use egw_table
   use egw_table_universal
   use egw_table_format
   use egw_hysteresis, only: hysteresis_table, build_hysteresis
   use egw_hysteresis_format, only: write_hysteresis
   implicit none
   type(force_table) :: t
   type(universal_table) :: u
   type(hysteresis_table) :: h
   type(egw_error), allocatable :: err
   call build_table(contact_params(model=model_egw, sigma=1e-3_dp, mu=4.0_dp), solver_options(), &
      & -6e-3_dp, 5e-2_dp, 1e-6_dp, t, err)
   if (allocated(err)) stop 1
   call write_table(t, "egw_1e-6.egwt", format_binary, err)
   print *, "1-D nodes", size(t%delta)
   call build_universal(model_egw, 0.0_dp, 0.6_dp, 54.0_dp, solver_options(), 2.0_dp, 8.0_dp, &
      & -3.0_dp, 30.0_dp, 1e-4_dp, u, err)
   if (allocated(err)) stop 2
   call write_universal(u, "egw_universal.egwu", format_binary, err)
   print *, "universal slices", u%n_mu, size(u%slices(1)%delta)
   call build_hysteresis(contact_params(model=model_epgw, sigma=1e-3_dp, mu=4.0_dp, psi=0.5_dp), &
      & solver_options(), -3e-3_dp, 3e-2_dp, 1e-4_dp, h, err)
   if (allocated(err)) stop 3
   call write_hysteresis(h, "epgw_1e-4.egwh", format_binary, err)
   print *, "hysteresis loading nodes", size(h%loading%delta)
end program make_tables

program read_bench
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_table
   use egw_table_universal
   use egw_table_format
   use egw_hysteresis, only: hysteresis_table
   use egw_hysteresis_format, only: read_hysteresis
   implicit none
   type(force_table) :: t
   type(universal_table) :: u
   type(hysteresis_table) :: h
   type(egw_error), allocatable :: err
   integer :: k, n
   real(dp) :: c0, c1
   character(len=16) :: arg
   call get_command_argument(1, arg)
   read (arg, *) n
   call cpu_time(c0)
   do k = 1, n
      call read_table("egw_1e-6.egwt", t, err)
      if (allocated(err)) stop 1
   end do
   call cpu_time(c1)
   write (*, '(a,f10.3)') "1-D table (E-GW 1e-6) read  [us/read]", (c1 - c0)/n*1e6
   call cpu_time(c0)
   do k = 1, n/10
      call read_universal("egw_universal.egwu", u, err)
      if (allocated(err)) stop 2
   end do
   call cpu_time(c1)
   write (*, '(a,f10.3)') "universal (E-GW 1e-4) read  [us/read]", (c1 - c0)/(n/10)*1e6
   call cpu_time(c0)
   do k = 1, n/10
      call read_hysteresis("epgw_1e-4.egwh", h, err)
      if (allocated(err)) stop 3
   end do
   call cpu_time(c1)
   write (*, '(a,f10.3)') "hysteresis (EP-GW 1e-4) read [us/read]", (c1 - c0)/(n/10)*1e6
end program read_bench
