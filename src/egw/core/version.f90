!> Library version, kept in step with fpm.toml.
module egw_version
   implicit none
   private
   integer, parameter, public :: egw_major = 0, egw_minor = 3, egw_patch = 6
   character(len=*), parameter, public :: egw_version_string = "0.3.6"
   !> 10000*major + 100*minor + patch, as returned by egw_get_version().
   integer, parameter, public :: egw_version_number = 10000*egw_major + 100*egw_minor + egw_patch
   public :: get_egw_version
contains
   !> The library's version as 10000*major + 100*minor + patch (egw_get_version in C).
   pure integer function get_egw_version()
      get_egw_version = egw_version_number
   end function get_egw_version
end module egw_version
