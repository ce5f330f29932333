!> The linear-algebra figures of one contact deck, for the scaling benchmark
!! (tools/bench_scaling.py runs it once per mesh, beside the runs of the
!! deck, so that every ratio compares figures of the same mesh and run):
!!
!!     bench_contact DECK [amd|metis]
!!
!! (the MUMPS ordering, default the solver's default: AMD or METIS's nested
!! dissection given as a user ordering, for the plain and the Schur
!! factorization alike)
!! The deck is read and numbered as kontakt2d does with the MUMPS solver,
!! K_AB assembled, and the pairs' reference springs K_ref added (as both
!! condensations do), then timed:
!! * one linear solve of the same mesh: MUMPS's analysis, factorization of
!!   K_AB + K_ref and one solve (one back-substitution);
!! * the contact system from MUMPS's Schur complement: analysis and
!!   factorization with the contact equations as Schur variables (its
!!   set-up), one condensation of a right-hand side, one expansion, one dense
!!   factorization of S + K_c (Cholesky) and one dense solve, directly and in
!!   the springs' own coordinates (contact_projection).
!! Output: one CSV line, in this order: neq, nc, nnz_factor (plain
!! factorization), analyse_s, assembly_s, factorize_s, solve_s, schur_s
!! (analysis + factorization with the Schur complement), condense_s,
!! expand_s, dense_factorize_s, dense_solve_s (the direct dense system),
!! proj_setup_s, proj_factorize_s, proj_solve_s (the same in the springs' own
!! coordinates: set-up once, then per set of springs), peak_rss_mb (VmHWM),
!! max_rel_diff (largest difference of the Schur path's solution from the
!! plain solve's, relative to its largest entry), ordering (the ordering
!! MUMPS used: amd or metis), ordering_s (METIS's time in analyse_s, 0 for
!! AMD), schur_analyse_s (the analysis in schur_s, ordering included),
!! schur_ordering_s (METIS's time in it), nnz_factor_schur (entries of the
!! factors of K_bb and the complement).  CPU times (cpu_time, one
!! thread: OPENBLAS_NUM_THREADS=1 is the benchmark's setting).
program bench_contact
   use kinds, only: dp, i8
   use errors, only: status_t, error_list_t
   use model, only: model_t
   use dof_map, only: dof_map_t
   use model_input, only: read_model
   use equation_numbering, only: numbering_report_t, number_equations
   use run_plan, only: run_plan_t, ORDERING_USER
   use linear_solver, only: linear_solver_t
   use solver_factory, only: create_solver
   use assembly, only: coupling_t, assemble_bodies
   use contact_assembly, only: contact_springs_t, pair_links
   use contact_system, only: contact_equations
   use contact_dense, only: contact_dense_t
#ifdef KONTAKT2D_HAVE_MUMPS
   use mumps_solver, only: mumps_solver_t, ORDERING_AMD, ORDERING_METIS
#endif
   implicit none

   type(model_t) :: m
   type(error_list_t) :: errs, warns
   type(dof_map_t) :: map
   type(numbering_report_t) :: rep
   type(status_t) :: st
   type(coupling_t) :: coup
   type(contact_springs_t) :: springs
   type(contact_dense_t) :: dense
   class(linear_solver_t), allocatable :: s
   integer, allocatable :: xadj(:), adjncy(:), links(:, :), ceq(:), pos(:), ppos(:, :)
   real(dp), allocatable :: diag(:), kref(:, :, :), b(:), x(:), y(:), g(:), dk(:, :, :)
   character(len=512) :: deck
   type(run_plan_t) :: plan
   character(len=16) :: ord
   integer :: j, k, nc
   integer(i8) :: nnzf, nnzs
   real(dp) :: t0, t_an, t_as, t_fa, t_so, t_sc, t_co, t_ex, t_df, t_ds, t_ps, t_pf, t_pv, t_or, t_sa, t_so2

   call get_command_argument(1, deck)
   if (len_trim(deck) == 0) stop 'usage: bench_contact DECK'
   call read_model(trim(deck), m, errs, warns)
   if (errs%count() > 0) then
      call errs%print()
      stop 2
   end if
   call pair_links(m%contact%pairs, links)
   plan%ordering = ORDERING_USER       ! the mesh's order: MUMPS orders the equations itself
   plan%ordering_reason = 'MUMPS orders the equations'
   call number_equations(m, plan, links, map, xadj, adjncy, rep, st, ties=m%ties)
   call check('numbering')
   call get_command_argument(2, ord)
   call create_solver('mumps', s, st)
   call check('create_solver')
   t_or = 0.0_dp
   call cpu_time(t0)
#ifdef KONTAKT2D_HAVE_MUMPS
   select type (s)
   type is (mumps_solver_t)
      select case (trim(ord))
      case ('amd')
         s%ordering = ORDERING_AMD
      case ('metis')
         s%ordering = ORDERING_METIS
      case ('')
      case default
         stop 'bench_contact: the ordering is amd or metis'
      end select
      call s%analyse(map%neq, xadj, adjncy, st)
      call check('analyse')
      ! MUMPS's analysis now (else at the first factorization), timed with the pattern's set-up
      call s%run_analysis(st)
      call check('analysis')
      t_or = s%ordering_seconds
      ord = 'amd'
      if (s%ordering_of_analysis() == ORDERING_METIS) ord = 'metis'
   end select
#endif
   t_an = elapsed(t0)
   call s%zero()
   allocate (diag(map%neq))
   call cpu_time(t0)
   call assemble_bodies(m, map, s, coup, st, diag)
   call check('assembly')
   t_as = elapsed(t0)
   call s%store_base()
   call springs%init(map, m%contact%pairs)
   call springs%reference_springs(m%contact%pairs, diag, kref)
   ceq = contact_equations(springs%peq, map%neq)
   nc = size(ceq)
   allocate (b(map%neq), x(map%neq), y(map%neq), g(nc))
   do k = 1, map%neq
      b(k) = sin(real(k, dp))
   end do

   ! one linear solve of the mesh: K_AB + K_ref factorized, one solve
   call with_reference_springs()
   call cpu_time(t0)
   call s%factorize(st)
   call check('factorize')
   t_fa = elapsed(t0)
   nnzf = s%stats%nnz_factor
   x = b
   call cpu_time(t0)
   call s%solve(x, st)
   call check('solve')
   t_so = elapsed(t0)

#ifdef KONTAKT2D_HAVE_MUMPS
   ! the Schur complement onto the contact equations from the factorization
   call dense%init(nc, size(springs%peq, 1), size(springs%peq, 2))
   call with_reference_springs()
   select type (s)
   type is (mumps_solver_t)
      call cpu_time(t0)
      call s%factorize_schur(ceq, dense%s, st)
      call check('factorize_schur')
      t_sc = elapsed(t0)
      t_sa = s%analysis_seconds
      t_so2 = s%ordering_seconds
      nnzs = s%stats%nnz_factor
      call cpu_time(t0)
      call s%schur_condense(b, g, st)
      call check('schur_condense')
      t_co = elapsed(t0)
      ! the dense system with the reference springs alone: K_AB + K_ref again
      allocate (pos(map%neq), ppos(size(springs%peq, 1), size(springs%peq, 2)))
      pos = 0
      pos(ceq) = [(k, k=1, nc)]
      ppos = 0
      do j = 1, size(ppos, 2)
         do k = 1, size(ppos, 1)
            if (springs%peq(k, j) > 0) ppos(k, j) = pos(springs%peq(k, j))
         end do
      end do
      allocate (dk, mold=kref)
      dk = 0.0_dp
      call cpu_time(t0)
      call dense%set_springs(ppos, dk, st)
      call check('dense factorization')
      t_df = elapsed(t0)
      call cpu_time(t0)
      call dense%solve(g, st)
      call check('dense solve')
      t_ds = elapsed(t0)
      call cpu_time(t0)
      call s%schur_expand(g, y, st)
      call check('schur_expand')
      t_ex = elapsed(t0)
      ! the same dense system in the springs' own coordinates
      call cpu_time(t0)
      call dense%prepare_projection(ppos, kref)
      t_ps = elapsed(t0)
      dk = -0.5_dp*kref          ! springs of half the reference stiffness: K_c - K_ref = -K_ref/2
      call cpu_time(t0)
      call dense%set_springs(ppos, dk, st)
      call check('dense factorization in the springs'' coordinates')
      t_pf = elapsed(t0)
      if (.not. dense%projected) stop 'bench_contact: the springs'' coordinates were not used'
      g = y(ceq)
      call cpu_time(t0)
      call dense%solve(g, st)
      t_pv = elapsed(t0)
   end select
#else
   stop 'bench_contact: built without MUMPS'
#endif
   write (*, '(i0,",",i0,",",i0,12(",",es12.5),",",f0.1,",",es10.3,",",a,3(",",es12.5),",",i0)') map%neq, nc, &
      nnzf, t_an, t_as, t_fa, t_so, t_sc, t_co, t_ex, t_df, t_ds, t_ps, t_pf, t_pv, peak_rss_mb(), &
      maxval(abs(y - x))/maxval(abs(x)), trim(ord), t_or, t_sa, t_so2, nnzs

contains

   subroutine with_reference_springs()
      integer :: jp
      call s%restore_base()
      do jp = 1, size(springs%peq, 2)
         call s%add_element(springs%peq(:, jp), kref(:, :, jp))
      end do
   end subroutine with_reference_springs

   subroutine check(what)
      character(len=*), intent(in) :: what
      if (st%ok()) return
      write (*, '(a)') 'bench_contact: '//what//': '//st%message
      stop 1
   end subroutine check

   real(dp) function elapsed(t_start)
      real(dp), intent(in) :: t_start
      real(dp) :: t1
      call cpu_time(t1)
      elapsed = t1 - t_start
   end function elapsed

   !> Peak resident memory of the process [MB] (VmHWM of /proc/self/status).
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
            if (ios == 0) peak_rss_mb = kb/1024.0_dp
            exit
         end if
      end do
      close (u)
   end function peak_rss_mb
end program bench_contact
