!> One run of the solver benchmark: a plane-strain block of Q4 elements,
!! numbered, assembled, factorized and solved with one solver; prints one
!! CSV line (see tools/bench_solvers.py, which runs this program once per
!! mesh and solver so that the peak memory of each run is its own).
!!
!!     bench_solvers SOLVER RENUMBER NX GRADE [OPTION [NSOLVE [SOLUTION]]]
!!
!! SOLVER skyline, umfpack or mumps; RENUMBER RCM or NONE (NONE keeps the
!! mesh generator's row-by-row numbering); NX elements per side (NX x NX
!! block); GRADE the ratio of the last to the first cell in x and y (1 =
!! uniform); OPTION (-1 = the solver's default) UMFPACK's steps of iterative
!! refinement or MUMPS's ordering (ICNTL(7)); NSOLVE solves of the same
!! right-hand side, timed together (default 1); SOLUTION a file that gets the
!! solution, neq doubles in native byte order (stream access).
!! Output columns: solver, renumber, nx, grade, neq, nnz_factor,
!! analyse_s, assembly_s, factorize_s, solve_s (mean of the NSOLVE solves),
!! peak_rss_mb (VmHWM), solver_mb (the solver's own figure), max_u, option,
!! residual (max |b - K x| / max |b|, K x summed element by element).
!! Wall-clock times.
program bench_solvers
   use kinds, only: dp, i8
   use errors, only: status_t
   use model, only: model_t, material_t, restraint_t, point_load_t
   use mesh_generator, only: generate_block
   use dof_map, only: dof_map_t
   use equation_numbering, only: numbering_report_t, number_equations
   use linear_solver, only: linear_solver_t
   use solver_factory, only: create_solver, plan_run
   use run_plan, only: run_plan_t
   use assembly, only: coupling_t, assemble_bodies, element_equations
   use solid2d, only: element_stiffness
   use model, only: MAX_NODE
#ifdef KONTAKT2D_HAVE_UMFPACK
   use umfpack_solver, only: umfpack_solver_t
#endif
#ifdef KONTAKT2D_HAVE_MUMPS
   use mumps_solver, only: mumps_solver_t
#endif
   implicit none

   type(model_t) :: m
   type(dof_map_t) :: map
   type(numbering_report_t) :: rep
   type(status_t) :: st
   type(run_plan_t) :: plan
   character(len=:), allocatable :: plan_name
   type(coupling_t) :: coup
   class(linear_solver_t), allocatable :: s
   integer, allocatable :: xadj(:), adjncy(:), nolinks(:, :)
   real(dp), allocatable :: rhs(:), b(:), x(:)
   character(len=32) :: a_solver, a_ren, a_nx, a_grade, a_opt, a_ns
   character(len=512) :: a_sol
   integer :: nx, ip, option, nsolve, k
   real(dp) :: grade, t_an, t_as, t_fa, t_so, umax
   integer(i8) :: c0, c1, rate

   call get_command_argument(1, a_solver)
   call get_command_argument(2, a_ren)
   call get_command_argument(3, a_nx)
   call get_command_argument(4, a_grade)
   call get_command_argument(5, a_opt)
   call get_command_argument(6, a_ns)
   call get_command_argument(7, a_sol)
   read (a_nx, *) nx
   read (a_grade, *) grade
   option = -1
   nsolve = 1
   if (len_trim(a_opt) > 0) read (a_opt, *) option
   if (len_trim(a_ns) > 0) read (a_ns, *) nsolve

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
   call plan_run(m, trim(a_solver), plan, plan_name)   ! the ordering as a run would choose it
   call number_equations(m, plan, nolinks, map, xadj, adjncy, rep, st)
   call create_solver(a_solver, s, st)
   call check('create_solver')
   if (option >= 0) then
      select type (s)
#ifdef KONTAKT2D_HAVE_UMFPACK
      type is (umfpack_solver_t)
         s%refine_steps = option
#endif
#ifdef KONTAKT2D_HAVE_MUMPS
      type is (mumps_solver_t)
         s%ordering = option
#endif
      end select
   end if
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

   allocate (b(map%neq))
   b = 0.0_dp
   do ip = 1, m%npoin
      if (m%coord(2, ip) > 1.0_dp - 1.0e-12_dp .and. map%id(2, ip) > 0) b(map%id(2, ip)) = -1.0_dp
   end do
   rhs = b
   call system_clock(c0)
   do k = 1, nsolve
      rhs = b
      call s%solve(rhs, st)
      call check('solve')
   end do
   call system_clock(c1)
   t_so = real(c1 - c0, dp)/real(rate, dp)/real(nsolve, dp)
   umax = maxval(abs(rhs))
   x = rhs
   if (len_trim(a_sol) > 0) then
      open (newunit=k, file=trim(a_sol), access='stream', form='unformatted', status='replace', action='write')
      write (k) x
      close (k)
   end if

   write (*, '(a,",",a,",",i0,",",f0.3,",",i0,",",i0,4(",",es10.3),",",f0.1,",",f0.1,",",es14.7,",",i0,",",es10.3)') &
      trim(a_solver), trim(rep%method), nx, grade, map%neq, s%stats%nnz_factor, t_an, t_as, t_fa, t_so, &
      peak_rss_mb(), real(s%stats%memory_bytes, dp)/1.0e6_dp, umax, option, residual(x, b)
contains
   !> max |b - K x| / max |b|, with K x summed element by element (restrained
   !! dofs are zero), independently of the solver.
   real(dp) function residual(x, b)
      real(dp), intent(in) :: x(:), b(:)
      real(dp) :: estif(2*MAX_NODE, 2*MAX_NODE), elcod(2, MAX_NODE), r(size(b))
      integer :: ieq(2*MAX_NODE), gdof(2*MAX_NODE), ie, nn, nevab, ierr, i, j, imat
      r = b
      do ie = 1, m%nelem
         nn = m%nnode_e(ie)
         imat = m%matno(ie)
         elcod(:, 1:nn) = m%coord(:, m%lnods(1:nn, ie))
         call element_stiffness(m%ntype, nn, elcod(:, 1:nn), m%mats(imat)%young, m%mats(imat)%poiss, &
                                m%mats(imat)%thick, m%ngaus, estif(1:2*nn, 1:2*nn), ierr)
         call element_equations(m, map, ie, ieq, gdof, nevab)
         do j = 1, nevab
            if (ieq(j) <= 0) cycle
            do i = 1, nevab
               if (ieq(i) > 0) r(ieq(i)) = r(ieq(i)) - estif(i, j)*x(ieq(j))
            end do
         end do
      end do
      residual = maxval(abs(r))/maxval(abs(b))
   end function residual

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
