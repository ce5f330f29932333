!> The incremental driver: owns the loop over load increments.
!!
!! Set-up: equation numbering, equation graph, symbolic analysis, K_AB
!! assembled once (bodies are linear elastic, small strain: eq. 4.12) and kept
!! in the solver as its base matrix, load vectors of every load case.
!! Per increment i: the increments of every load case's factor scale the
!! external forces and the prescribed displacements; the system is solved for
!! the displacement increment; totals are sums of increments (eqs. 3.34-3.35);
!! stresses and reactions are recovered; the increment is written to the HDF5
!! file and flushed.
!!
!! A numerical failure (singular matrix, ...) stops the loop cleanly: every
!! finished increment stays in the result file, whose status attribute says
!! what happened.
module incremental
   use kinds, only: dp, stdout, stderr
   use errors, only: status_t, STAT_SINGULAR, STAT_INPUT, STAT_IO, STAT_JACOBIAN
   use strings, only: itoa, rtoa, strip_extension, basename
   use model, only: model_t, MAX_NODE
   use dof_map, only: dof_map_t
   use equation_numbering, only: numbering_report_t, number_equations, write_numbering_report
   use linear_solver, only: linear_solver_t
   use solver_factory, only: create_solver
   use assembly, only: coupling_t, assemble_bodies, assemble_load_cases, element_equations, &
                       subtract_prescribed, restrained_forces, element_error
   use solid2d, only: element_stresses
   use quadrature, only: max_gp
   use results_hdf5, only: results_file_t, K2D_VERSION
   use listing, only: list_header, list_input, list_displacements, list_stresses
   use hdf5, only: hid_t
   implicit none
   private
   public :: run_options_t, run_result_t, run_analysis, recover_stresses

   !> Choices of the command line that override or complement the deck.
   type :: run_options_t
      character(len=:), allocatable :: results_path   !! HDF5 file ('' = <deck>.h5 in the working directory)
      character(len=:), allocatable :: listing_path   !! listing file ('' = <deck>.lis next to the results)
      character(len=:), allocatable :: solver_name    !! '' = the deck's choice
      logical :: quiet = .false.                      !! no terminal output except errors
   end type run_options_t

   !> What a run leaves in memory (used by the tests and the caller).
   type :: run_result_t
      integer :: completed = 0                   !! increments finished
      real(dp), allocatable :: disp(:, :)        !! (2, npoin) total displacements
      real(dp), allocatable :: react(:, :)       !! (2, npoin) reactions
      real(dp), allocatable :: sig_nd(:, :)      !! (4, npoin) averaged nodal stresses
      real(dp), allocatable :: sig_gp(:, :)      !! (4, ngp) Gauss-point stresses
      real(dp), allocatable :: xygp(:, :)        !! (2, ngp)
      integer, allocatable :: gp_start(:)        !! (nelem+1)
      character(len=:), allocatable :: results_path
   end type run_result_t

contains

   !> Solve the model through its load history.
   subroutine run_analysis(m, opts, res, status)
      type(model_t), intent(inout) :: m
      type(run_options_t), intent(in) :: opts
      type(run_result_t), intent(out) :: res
      type(status_t), intent(inout) :: status
      type(dof_map_t) :: map
      class(linear_solver_t), allocatable :: solver
      type(coupling_t) :: coup
      type(results_file_t) :: rf
      integer, allocatable :: xadj(:), adjncy(:), nolinks(:, :)
      type(numbering_report_t) :: numbering
      real(dp), allocatable :: fcase(:, :, :), ucase(:, :, :), fext(:, :), du(:, :), rhs(:), fr(:, :)
      real(dp), allocatable :: dlam(:)
      logical, allocatable :: restrained(:, :)
      integer :: ip, inc, ieq, lu, ic
      integer(hid_t) :: gid
      integer(kind=8) :: t0, t1, rate
      character(len=:), allocatable :: solver_name, base, lis_path, lis_level
      logical :: factored

      call system_clock(t0, rate)
      solver_name = m%solver_name
      if (allocated(opts%solver_name)) then
         if (len(opts%solver_name) > 0) solver_name = opts%solver_name
      end if
      base = strip_extension(basename(m%deck_file))
      res%results_path = base//'.h5'
      if (allocated(opts%results_path)) then
         if (len(opts%results_path) > 0) res%results_path = opts%results_path
      end if
      lis_path = strip_extension(res%results_path)//'.lis'
      if (allocated(opts%listing_path)) then
         if (len(opts%listing_path) > 0) lis_path = opts%listing_path
      end if
      lis_level = m%listing_level

      ! ---- equations, pattern, K_AB
      allocate (nolinks(2, 0))
      call number_equations(m, solver_name, nolinks, map, xadj, adjncy, numbering, status)
      if (.not. status%ok()) return
      call create_solver(solver_name, solver, status)
      if (.not. status%ok()) then
         status%code = STAT_INPUT
         return
      end if
      call solver%analyse(map%neq, xadj, adjncy, status)
      if (.not. status%ok()) return
      call solver%zero()
      call assemble_bodies(m, map, solver, coup, status)
      if (.not. status%ok()) return
      call solver%store_base()
      call assemble_load_cases(m, fcase, ucase, status)
      if (.not. status%ok()) return

      allocate (restrained(2, m%npoin))
      restrained = map%id < 0
      allocate (res%disp(2, m%npoin), res%react(2, m%npoin), fext(2, m%npoin), du(2, m%npoin), &
                rhs(map%neq), fr(2, m%npoin), dlam(m%ncase))
      res%disp = 0.0_dp
      res%react = 0.0_dp
      fext = 0.0_dp

      ! ---- stress recovery layout (Gauss points are fixed)
      call recover_stresses(m, res%disp, res%gp_start, res%xygp, res%sig_gp, res%sig_nd, status)
      if (.not. status%ok()) return

      ! ---- result file and listing
      call rf%create(res%results_path, m, res%gp_start(2:) - res%gp_start(:m%nelem), res%xygp, status)
      if (.not. status%ok()) return
      lu = -1
      if (lis_level /= 'NONE') then
         open (newunit=lu, file=lis_path, status='replace', action='write')
         call list_header(lu, m, K2D_VERSION, solver%name(), map%neq, map%nres)
         call write_numbering_report(lu, numbering)
         if (lis_level == 'FULL') call list_input(lu, m)
      end if
      if (.not. opts%quiet) then
         call list_header(stdout, m, K2D_VERSION, solver%name(), map%neq, map%nres)
         call write_numbering_report(stdout, numbering)
         write (stdout, '(a)') ' Results      : '//res%results_path
         if (lu > 0) write (stdout, '(a)') ' Listing      : '//lis_path
         write (stdout, '(a)') repeat('-', 78)
         write (stdout, '(a)') '   inc  load factor     max |u|        sum Rx        sum Ry    time [s]'
      end if

      ! ---- the loop over increments
      factored = .false.
      do inc = 1, m%nincs
         dlam = m%lambda(:, inc) - m%lambda(:, inc - 1)
         du = 0.0_dp
         rhs = 0.0_dp
         do ic = 1, m%ncase
            fext = fext + dlam(ic)*fcase(:, :, ic)
            where (restrained) du = du + dlam(ic)*ucase(:, :, ic)
         end do
         do ip = 1, m%npoin
            do ieq = 1, 2
               if (map%id(ieq, ip) > 0) then
                  rhs(map%id(ieq, ip)) = rhs(map%id(ieq, ip)) + sum(dlam*fcase(ieq, ip, :))
               end if
            end do
         end do
         call subtract_prescribed(coup, map, du, rhs)

         if (.not. factored) then
            call solver%restore_base()
            call solver%factorize(status)
            if (.not. status%ok()) then
               if (status%code == STAT_SINGULAR .and. solver%failed_equation() > 0) then
                  status%message = 'singular or unrestrained model at '// &
                                   map%describe(solver%failed_equation())//': '//status%message
               end if
               exit
            end if
            factored = .true.
         end if
         call solver%solve(rhs, status)
         if (.not. status%ok()) exit
         do ip = 1, m%npoin
            do ieq = 1, 2
               if (map%id(ieq, ip) > 0) du(ieq, ip) = rhs(map%id(ieq, ip))
            end do
         end do
         res%disp = res%disp + du

         ! ---- post-processing
         call recover_stresses(m, res%disp, res%gp_start, res%xygp, res%sig_gp, res%sig_nd, status)
         if (.not. status%ok()) exit
         call restrained_forces(coup, map, res%disp, fr)
         res%react = 0.0_dp
         where (restrained) res%react = fr - fext

         call rf%open_increment(inc, m%lambda(:, inc), 1, 0, .true., gid, status)
         if (.not. status%ok()) exit
         block
            integer :: err
            err = 0
            call rf%write_real2(gid, 'displacement', res%disp, err)
            call rf%write_real2(gid, 'stress_nodal', res%sig_nd, err)
            call rf%write_real2(gid, 'stress_gauss', res%sig_gp, err)
            call rf%write_real2(gid, 'reaction', res%react, err)
            if (err < 0) call status%set(STAT_IO, 'HDF5: cannot write the results of increment '//itoa(inc))
         end block
         if (.not. status%ok()) exit
         call rf%close_increment(gid, status)
         if (.not. status%ok()) exit
         res%completed = inc

         if (lu > 0 .and. (lis_level == 'FULL' .or. inc == m%nincs)) then
            call list_displacements(lu, m, inc, m%lambda(:, inc), res%disp, res%react, restrained)
            call list_stresses(lu, m, res%gp_start, res%xygp, res%sig_gp)
         end if
         call system_clock(t1)
         if (.not. opts%quiet) then
            write (stdout, '(i6, f13.5, 3es14.5, f12.3)') inc, maxval(abs(m%lambda(:, inc))), &
               maxval(sqrt(res%disp(1, :)**2 + res%disp(2, :)**2)), sum(res%react(1, :)), &
               sum(res%react(2, :)), real(t1 - t0, dp)/real(rate, dp)
            flush (stdout)
         end if
      end do

      if (status%ok()) then
         call rf%set_status('completed')
         if (.not. opts%quiet) then
            write (stdout, '(a)') repeat('-', 78)
            write (stdout, '(a)') ' Completed '//itoa(res%completed)//' increment(s); results in '//res%results_path
         end if
      else
         call rf%set_status('failed at increment '//itoa(res%completed + 1)//': '//status%message)
         write (stderr, '(a)') 'kontakt2d: increment '//itoa(res%completed + 1)//' failed: '//status%message
         write (stderr, '(a)') 'kontakt2d: '//itoa(res%completed)//' completed increment(s) are kept in '// &
            res%results_path
      end if
      call rf%close()
      if (lu > 0) close (lu)
      call solver%free()
   end subroutine run_analysis

   !> Stresses at every Gauss point and averaged at the nodes.
   subroutine recover_stresses(m, disp, gp_start, xygp, sig_gp, sig_nd, status)
      type(model_t), intent(in) :: m
      real(dp), intent(in) :: disp(:, :)
      integer, allocatable, intent(inout) :: gp_start(:)
      real(dp), allocatable, intent(inout) :: xygp(:, :), sig_gp(:, :), sig_nd(:, :)
      type(status_t), intent(inout) :: status
      real(dp) :: elcod(2, MAX_NODE), eldis(2*MAX_NODE), xyg(2, max_gp), sg(4, max_gp), sn(4, MAX_NODE)
      real(dp), allocatable :: cnt(:)
      integer :: ie, nn, ngp, ierr, k, imat, pass

      pass = 2
      if (.not. allocated(gp_start)) pass = 1
      if (pass == 1) then
         ! first call: count the Gauss points
         allocate (gp_start(m%nelem + 1))
         gp_start(1) = 1
         do ie = 1, m%nelem
            nn = m%nnode_e(ie)
            elcod(:, 1:nn) = m%coord(:, m%lnods(1:nn, ie))
            imat = m%matno(ie)
            call element_stresses(m%ntype, nn, elcod(:, 1:nn), m%mats(imat)%young, m%mats(imat)%poiss, &
                                  m%ngaus, [(0.0_dp, k=1, 2*nn)], ngp, xyg, sg, sn(:, 1:nn), ierr)
            gp_start(ie + 1) = gp_start(ie) + ngp
         end do
         allocate (xygp(2, gp_start(m%nelem + 1) - 1), sig_gp(4, gp_start(m%nelem + 1) - 1), sig_nd(4, m%npoin))
      end if
      allocate (cnt(m%npoin))
      cnt = 0.0_dp
      sig_nd = 0.0_dp
      do ie = 1, m%nelem
         nn = m%nnode_e(ie)
         imat = m%matno(ie)
         elcod(:, 1:nn) = m%coord(:, m%lnods(1:nn, ie))
         do k = 1, nn
            eldis(2*k - 1:2*k) = disp(:, m%lnods(k, ie))
         end do
         call element_stresses(m%ntype, nn, elcod(:, 1:nn), m%mats(imat)%young, m%mats(imat)%poiss, &
                               m%ngaus, eldis(1:2*nn), ngp, xyg, sg, sn(:, 1:nn), ierr)
         if (ierr /= 0) then
            call status%set(STAT_JACOBIAN, 'element '//itoa(ie)//' (stress recovery): '//element_error(ierr))
            return
         end if
         xygp(:, gp_start(ie):gp_start(ie + 1) - 1) = xyg(:, 1:ngp)
         sig_gp(:, gp_start(ie):gp_start(ie + 1) - 1) = sg(:, 1:ngp)
         do k = 1, nn
            sig_nd(:, m%lnods(k, ie)) = sig_nd(:, m%lnods(k, ie)) + sn(:, k)
            cnt(m%lnods(k, ie)) = cnt(m%lnods(k, ie)) + 1.0_dp
         end do
      end do
      do k = 1, m%npoin
         if (cnt(k) > 0.0_dp) sig_nd(:, k) = sig_nd(:, k)/cnt(k)
      end do
   end subroutine recover_stresses
end module incremental
