!> beyond31: instructions of one stateless hysteresis_eval above a rough + cap table's
!> delta_max (history 1.1 X, unloading), against one inside it (history 0.9 X), for
!> doc/benchmarks.md "Stop 65: beyond31". Build against a library's modules and archive:
!>   gfortran -O2 -fopenmp -I MODS tools/bench/beyond31_beyond_cost.f90 LIB/libegw.a \
!>     -lfftw3_omp -lfftw3 -llapack -lblas -o /tmp/bc
!> Run: valgrind --tool=cachegrind --cache-sim=no /tmp/bc TABLE.bin {in|beyond} N
!> (the difference of two N's instruction counts over their difference in N: per call).
program beyond31_beyond_cost
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_hysteresis, only: hysteresis_table, hysteresis_eval
   use egw_hysteresis_format, only: read_hysteresis
   implicit none
   type(hysteresis_table) :: table
   type(egw_error), allocatable :: err
   character(len=512) :: path, where, arg
   real(dp) :: m, h, f, k, total, x
   integer :: n, i, stat, bad
   call get_command_argument(1, path)
   call get_command_argument(2, where)
   call get_command_argument(3, arg)
   read (arg, *) n
   call read_hysteresis(trim(path), table, err)
   if (allocated(err)) error stop "read failed"
   x = table%delta_max
   m = 0.9_dp*x
   if (trim(where) == "beyond") m = 1.1_dp*x
   total = 0
   bad = 0
   do i = 1, n
      h = m
      call hysteresis_eval(table, m*(1 - 0.1_dp*real(mod(i, 97), dp)/97), h, f, k, stat)
      total = total + f
      if (stat /= 0) bad = bad + 1
   end do
   print *, trim(where), n, total, " calls with stat /= 0:", bad
end program beyond31_beyond_cost
