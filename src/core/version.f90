!> The program's version, for the banner, `--version` and the result file.
!!
!! In `core` so that every layer (the command line, the listing, the result
!! file) can name it without using a module of another layer.
module version
   implicit none
   private

   character(len=*), parameter, public :: K2D_VERSION = '0.1.0'   !! program version
end module version
