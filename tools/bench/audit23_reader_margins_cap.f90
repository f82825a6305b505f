! audit23: as audit23_reader_margins.f90, for hysteresis tables with the cap (Hertz, GW, E-GW,
! EP-GW + cap; p_y 0.02 and 0.2 E*, 1e-2 and 1e-4)
program stats
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_params, only: contact_params, model_hertz, model_gw, model_egw, model_epgw
   use egw_rough_sphere, only: solver_options
   use egw_table
   use egw_table_universal
   use egw_hysteresis, only: hysteresis_table, build_hysteresis
   implicit none
   type(force_table) :: t
   type(universal_table) :: u
   type(hysteresis_table) :: h
   type(egw_error), allocatable :: err
   real(dp) :: tols(3) = [1e-2_dp, 1e-4_dp, 1e-6_dp], fps(3) = [0.0_dp, 0.02_dp, 0.2_dp]
   integer :: m, it, ip, j
   integer :: models(4) = [model_hertz, model_gw, model_egw, model_epgw]
   do m = 1, 4
      do ip = 2, 3
         do it = 1, 2
            if (m == 1) then
               call build_hysteresis(contact_params(model=models(m), flow_pressure=fps(ip)), &
                  & solver_options(), 0.0_dp, 30*(3.14159_dp*fps(ip)/2)**2, tols(it), h, err)
            else
               call build_hysteresis(contact_params(model=models(m), sigma=1e-4_dp, mu=4.0_dp, &
                  & psi=0.5_dp, flow_pressure=fps(ip)), solver_options(), -3e-4_dp, &
                  & 10*(3.14159_dp*fps(ip)/2)**2, tols(it), h, err)
            end if
            if (allocated(err)) then
               print *, "C", m, ip, it, "ERR ", err%message
               deallocate (err)
            else
               call report("C", m*100 + ip*10 + it, h%loading)
            end if
         end do
      end do
   end do
contains
   subroutine report(tag, id, t)
      character(len=*), intent(in) :: tag
      integer, intent(in) :: id
      type(force_table), intent(in) :: t
      integer :: i, n
      real(dp) :: hh, p0, p1, d0, d1, rise, ratio, minr, igr, we, maxe
      logical :: in_log
      n = size(t%delta)
      minr = huge(1.0_dp); maxe = 0
      do i = 1, n - 1
         in_log = i <= t%n_log
         hh = t%delta(i + 1) - t%delta(i)
         p0 = t%force(i); p1 = t%force(i + 1)
         if (in_log) then
            rise = log(p1) - log(p0); d0 = hh*t%stiffness(i)/p0; d1 = hh*t%stiffness(i + 1)/p1
         else
            rise = p1 - p0; d0 = hh*t%stiffness(i); d1 = hh*t%stiffness(i + 1)
         end if
         if (p1 - p0 > 1e3_dp*epsilon(1.0_dp)*p1) then
            ratio = max(d0, d1)/rise
            minr = min(minr, ratio)
         end if
         if (.not. in_log) then
            igr = hh*(p0 + p1)/2 + hh*hh*(t%stiffness(i) - t%stiffness(i + 1))/12
            we = abs((t%energy(i + 1) - t%energy(i)) - igr)/(hh*max(p0, p1) + tiny(1.0_dp))
            maxe = max(maxe, we)
         end if
      end do
      print '(a,1x,i6,1x,i5,1x,i4,2(1x,es10.3))', tag, id, n, t%n_log, minr, maxe
   end subroutine report
end program stats
