!> One run of the solver benchmark: a plane-strain block of Q4 elements,
!! numbered, assembled, factorized and solved with one solver; prints one
!! CSV line (see tools/bench_solvers.py, which runs this program once per
!! mesh and solver so that the peak memory of each run is its own).
!!
!!     bench_solvers SOLVER RENUMBER NX GRADE
!!
!! SOLVER skyline or umfpack; RENUMBER RCM or NONE (NONE keeps the mesh
!! generator's row-by-row numbering); NX elements per side (NX x NX block);
!! GRADE the ratio of the last to the first cell in x and y (1 = uniform).
!! Output columns: solver, renumber, nx, grade, neq, nnz_factor,
!! analyse_s, assembly_s, factorize_s, solve_s, peak_rss_mb (VmHWM),
!! solver_mb (the solver's own figure), max_u.
program bench_solvers
   use kinds, only: dp, i8
   use errors, only: status_t
   use model, only: model_t, material_t, restraint_t, point_load_t
   use mesh_generator, only: generate_block
   use dof_map, only: dof_map_t
   use equation_numbering, only: numbering_report_t, number_equations
   use linear_solver, only: linear_solver_t
   use solver_factory, only: create_solver
   use assembly, only: coupling_t, assemble_bodies
   implicit none

   type(model_t) :: m
   type(dof_map_t) :: map
   type(numbering_report_t) :: rep
   type(status_t) :: st
   type(coupling_t) :: coup
   class(linear_solver_t), allocatable :: s
   integer, allocatable :: xadj(:), adjncy(:), nolinks(:, :)
   real(dp), allocatable :: rhs(:)
   character(len=32) :: a_solver, a_ren, a_nx, a_grade
   integer :: nx, ip
   real(dp) :: grade, t_an, t_as, t_fa, t_so, umax
   integer(i8) :: c0, c1, rate

   call get_command_argument(1, a_solver)
   call get_command_argument(2, a_ren)
   call get_command_argument(3, a_nx)
   call get_command_argument(4, a_grade)
   read (a_nx, *) nx
   read (a_grade, *) grade

   m%title = 'bench'
   m%deck_file = 'bench.dat'
   m%ntype = 2
   m%renumber = trim(a_ren)
   m%solver_name = trim(a_solver)
   call generate_block(m, 4, nx, nx, 0.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, grade, grade)
   m%nmats = 1
   allocate (m%mats(1))
   m%mats(1) = material_t(young=2.1e5_dp, poiss=0.3_dp, thick=1.0_dp)
   ! bottom edge clamped, unit downward force at every top node
   allocate (m%fixes(0), m%point_loads(0), m%edge_loads(0), m%body_loads(0))
   do ip = 1, m%npoin
      if (m%coord(2, ip) < 1.0e-12_dp) m%fixes = [m%fixes, restraint_t(node=ip, fixed=[.true., .true.])]
   end do
   allocate (nolinks(2, 0))

   call system_clock(c0, rate)
   call number_equations(m, a_solver, nolinks, map, xadj, adjncy, rep, st)
   call create_solver(a_solver, s, st)
   call s%analyse(map%neq, xadj, adjncy, st)
   call check('analyse')
   call system_clock(c1)
   t_an = real(c1 - c0, dp)/real(rate, dp)

   c0 = c1
   call assemble_bodies(m, map, s, coup, st)
   call check('assembly')
   call system_clock(c1)
   t_as = real(c1 - c0, dp)/real(rate, dp)

   c0 = c1
   call s%factorize(st)
   call check('factorize')
   call system_clock(c1)
   t_fa = real(c1 - c0, dp)/real(rate, dp)

   allocate (rhs(map%neq))
   rhs = 0.0_dp
   do ip = 1, m%npoin
      if (m%coord(2, ip) > 1.0_dp - 1.0e-12_dp .and. map%id(2, ip) > 0) rhs(map%id(2, ip)) = -1.0_dp
   end do
   c0 = c1
   call s%solve(rhs, st)
   call check('solve')
   call system_clock(c1)
   t_so = real(c1 - c0, dp)/real(rate, dp)
   umax = maxval(abs(rhs))

   write (*, '(a,",",a,",",i0,",",f0.3,",",i0,",",i0,4(",",es10.3),",",f0.1,",",f0.1,",",es14.7)') &
      trim(a_solver), trim(rep%method), nx, grade, map%neq, s%stats%nnz_factor, t_an, t_as, t_fa, t_so, &
      peak_rss_mb(), real(s%stats%memory_bytes, dp)/1.0e6_dp, umax
contains
   subroutine check(what)
      character(len=*), intent(in) :: what
      if (.not. st%ok()) then
         write (*, '(a)') 'bench_solvers: '//what//' failed: '//st%message
         error stop 1
      end if
   end subroutine check

   !> Peak resident set size of this process (VmHWM of /proc/self/status), MB.
   real(dp) function peak_rss_mb()
      character(len=256) :: line
      integer :: u, ios, kb
      peak_rss_mb = -1.0_dp
      open (newunit=u, file='/proc/self/status', action='read', iostat=ios)
      if (ios /= 0) return
      do
         read (u, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (line(1:6) == 'VmHWM:') then
            read (line(7:), *, iostat=ios) kb
            if (ios == 0) peak_rss_mb = real(kb, dp)/1024.0_dp
            exit
         end if
      end do
      close (u)
   end function peak_rss_mb
end program bench_solvers
