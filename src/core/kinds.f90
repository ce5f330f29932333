!> Working precision and mathematical constants.
!!
!! The only module that touches `iso_fortran_env`; every other module takes
!! `dp` from here so that the working precision is set in one place.
module kinds
   use, intrinsic :: iso_fortran_env, only: real64, int64, output_unit, error_unit
   implicit none
   private

   integer, parameter, public :: dp = real64   !! working real kind
   integer, parameter, public :: i8 = int64    !! long integer kind (counters, memory)
   integer, parameter, public :: stdout = output_unit
   integer, parameter, public :: stderr = error_unit

   real(dp), parameter, public :: pi = 3.141592653589793238462643383279502884_dp
   real(dp), parameter, public :: two_pi = 2.0_dp*pi
end module kinds
