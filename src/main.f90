!> Kontakt2D command line (placeholder until the driver lands).
program kontakt2d
   implicit none
   print '(a)', 'kontakt2d: driver not yet built'
end program kontakt2d
