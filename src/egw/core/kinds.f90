!> Working precision and mathematical constants shared by every egw module.
module egw_kinds
   use, intrinsic :: iso_fortran_env, only: real64, int32, int64
   implicit none
   private

   !> Double precision, the only real kind egw computes in.
   integer, parameter, public :: dp = real64
   integer, parameter, public :: i4 = int32, i8 = int64

   real(dp), parameter, public :: pi = 3.141592653589793238462643383279502884_dp
   real(dp), parameter, public :: sqrt2 = 1.414213562373095048801688724209698079_dp
   real(dp), parameter, public :: sqrtpi = 1.772453850905516027298167483341145183_dp
   !> 1/sqrt(2 pi), the peak of the standard normal density.
   real(dp), parameter, public :: inv_sqrt2pi = 0.398942280401432677939946059934381868_dp

end module egw_kinds
