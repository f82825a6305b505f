!> The deep9 case of issue 32 / stop 65 (dbg31): EP-GW psi 1 + cap (R = 1, E* = 1, p_y =
!> 0.01, sigma = delta_y/100, mu 4), history loaded to M delta_y at rel_tol HTOL, then
!> unloading solves of that one history at each overlap FRACTION*M delta_y and each
!> rel_tol TOL. One line a solve: M, fraction, tol, force, est_rel_err, P(delta_max).
!>
!>   B=$(dirname $(find build -path '*/egw_hysteresis.mod' | head -1))
!>   gfortran -O2 -fopenmp -I$B tools/bench/dbg31_deep9.f90 \
!>      $(find build -name libegw.a | head -1) -lfftw3_omp -lfftw3 -llapack -lblas -o /tmp/d9
!>   OMP_NUM_THREADS=1 /tmp/d9 M HTOL "FRACTIONS" "TOLS"
!>   e.g. /tmp/d9 9.375 1e-6 "0.8837 0.8357" "1e-6 1e-8"
program deep9
   use egw, only: dp, contact_params, model_epgw, solver_options, egw_error, &
      & solve_result, loading_history, load_history, solve_unload
   implicit none
   real(dp), parameter :: pi = acos(-1.0_dp), py = 0.01_dp
   real(dp) :: dy, m, htol, fractions(200), tols(20)
   character(len=2000) :: arg
   integer :: nf, nt, i, j, ios
   type(contact_params) :: p
   type(loading_history) :: h
   type(solve_result) :: top, res
   type(egw_error), allocatable :: err
   call get_command_argument(1, arg); read (arg, *) m
   call get_command_argument(2, arg); read (arg, *) htol
   call get_command_argument(3, arg); nf = count_items(arg)
   read (arg, *, iostat=ios) fractions(1:nf)
   call get_command_argument(4, arg); nt = count_items(arg)
   read (arg, *, iostat=ios) tols(1:nt)
   dy = (0.5_dp*pi*py)**2
   p = contact_params(model=model_epgw, radius=1.0_dp, modulus=1.0_dp, sigma=0.01_dp*dy, &
      & mu=4.0_dp, psi=1.0_dp, flow_pressure=py)
   call load_history(p, solver_options(rel_tol=htol), m*dy, h, top, err)
   if (allocated(err)) then
      print '(a,1x,a)', "history FAIL", trim(err%message)
      stop 1
   end if
   do i = 1, nf
      do j = 1, nt
         h%options%rel_tol = tols(j)
         call solve_unload(h, fractions(i)*m*dy, res, err)
         if (allocated(err)) then
            print '(f10.5,1x,f10.6,1x,es8.1,1x,a,1x,a)', m, fractions(i), tols(j), "FAIL", &
               & trim(err%message)
            deallocate (err)
         else
            print '(f10.5,1x,f10.6,1x,es8.1,1x,es24.16,1x,es10.3,1x,es24.16)', m, &
               & fractions(i), tols(j), res%force, res%est_rel_err, top%force
         end if
         flush (6)
      end do
   end do
contains
   integer function count_items(s) result(n)
      character(len=*), intent(in) :: s
      integer :: k
      logical :: in_word
      n = 0
      in_word = .false.
      do k = 1, len_trim(s)
         if (s(k:k) /= ' ' .and. .not. in_word) n = n + 1
         in_word = s(k:k) /= ' '
      end do
   end function count_items
end program deep9
