!> HDF5 result file: the mesh once, then one group per increment.
!!
!! The only module that knows HDF5 and the names of the layout (documented in
!! docs/results-format.md; shapes as seen from C/Python):
!!
!!     /                       attributes: program, version, title, deck,
!!                             analysis_type, ntype, ncase, status,
!!                             increments_completed; the run information
!!                             (autoinc, autoinc_min_fraction,
!!                             autoinc_easy_solutions, condensed, max_repeats)
!!     /mesh/coordinates       (npoin, 2)   x, y  (r, z in axisymmetry)
!!     /mesh/connectivity      (nelem, 9)   1-based node numbers, zero padded
!!     /mesh/element_nodes     (nelem)      3, 4, 8 or 9
!!     /mesh/material          (nelem)
!!     /mesh/gauss_coordinates (ngp, 2)     Gauss points of all elements
!!     /mesh/gauss_element     (ngp)        element of each Gauss point
!!     /contact                the contact definition (contact models)
!!     /increments/NNNNN/      attributes from the step record: increment,
!!                             load_factor(ncase), iterations, repeats,
!!                             converged, residual, law_drift, ...
!!         displacement  (npoin, 2)
!!         displacement_xyz (npoin, 3)  the same with a zero third column (the
!!                       vector ParaView's Xdmf3 readers need for Warp By Vector)
!!         stress_nodal  (npoin, 4)  xx, yy, xy, zz (hoop in axisymmetry)
!!         stress_gauss  (ngp, 4)
!!         reaction      (npoin, 2)  zero at free dofs
!!         error_indicator (nelem)   relative energy-norm error of each element (attribute
!!                       estimated_error: that of the model), see docs/results-format.md
!!         contact/      the contact fields record (contact models)
!!
!! Life cycle, layout-level calls only (the caller holds no HDF5 handle):
!!
!!     call rf%create(path, m, body, status)          ! the mesh, status "running"
!!     call rf%write_run_info(info, status)           ! root attributes of the run
!!     call rf%write_contact_definition(c, info, status)
!!     call rf%write_header(m, info, numbering, status)  ! the rest of the listing's header
!!     do accepted step
!!        call rf%write_increment(step, body, status, contact)   ! one group, flushed
!!     end do
!!     call rf%write_cycles(tab, status)              ! /cycles (a periodic history)
!!     call rf%write_summary(s, status)               ! /summary: what the listing's summary says
!!     call rf%set_status(text)                       ! completed / doubtful: ... / failed at ...
!!     call rf%close()
!!
!! The file is flushed after every increment, so a run that stops early
!! leaves every finished increment readable.  Every HDF5 return code is
!! checked; a failure is returned as a status, never ignored.
!!
!! A full disk.  HDF5 (1.10) does not recover from a failed write: once a
!! flush has failed, no later flush, unlink or close succeeds, and what
!! reached the disk is a file whose groups point past its end.  So the disk
!! is never allowed to fill under HDF5:
!!  - `create` holds a reserve file beside the result file (`NAME.reserve`,
!!    RESERVE_BYTES allocated on the disk, module disk_reserve); at the end of the
!!    run (`write_summary`, `set_status`, `close`) it is deleted, which gives the summary,
!!    the last status,
!!    flush and close their room whatever the listing took meanwhile;
!!  - before the mesh, the contact definition and every increment group,
!!    `probe_room` allocates the bytes the group will take (its arrays plus a
!!    margin for HDF5's metadata) in the reserve file and then cuts the
!!    reserve back to its size: when the disk cannot hold them, nothing of
!!    the group is written, the reserve is released and the run ends with
!!    exit 3 and a readable file whose status names the increment that found
!!    no room.
!! Another process that fills the disk between the probe and the write can
!! still break the file: the probe is a check, not an allocation.  A disk
!! without room for the reserve ends the run before the first increment, with
!! no result file.
module results_hdf5
   use, intrinsic :: iso_c_binding, only: c_double
   use hdf5
   use kinds, only: dp, i8
   use errors, only: status_t, STAT_IO, skip_exit_handlers
   use strings, only: itoa
   use model, only: model_t, ntype_name, MAX_NODE
   use records, only: step_record_t, body_fields_t, contact_fields_t, run_info_t, cycle_table_t
   use records, only: numbering_report_t
   use run_plan, only: solver_name, choice_name, system_name, ordering_name, scheme_name, &
         CHOICE_AUTOMATIC
   use contact_types, only: contact_def_t, units_name, friction_name, update_name, slip_name, &
         law_name, &
                            matching_name, rigid_shape_name, MAX_PAIR_NODES
   use version, only: K2D_VERSION
   use disk_reserve, only: reserve_t
   use run_summary, only: run_summary_t
   use xdmf_writer, only: write_xdmf, xdmf_path, CELL_NNODE, XDMF_CELL_CODE
   implicit none
   private
   public :: results_file_t


   type :: results_file_t
      private
      integer(hid_t) :: fid = -1
      character(len=:), allocatable :: path
      integer :: ncompleted = 0
      logical :: opened = .false.
      ! what the XDMF sidecar needs (see xdmf_writer)
      integer :: npoin = 0
      integer :: ncells(4) = 0                 !! elements of each kind: T3, Q4, Q8, Q9
      integer :: nmixed = 0                    !! length of /mesh/cells_mixed (mixed meshes)
      integer :: npair = 0                     !! contact pairs (the sidecar's contact grid)
      integer, allocatable :: incs(:)          !! finished increments (1:ncompleted;
                                               !! grown by doubling)
      real(dp), allocatable :: lambda(:, :)    !! (ncase, 1:ncompleted) their load factors
      integer :: xdmf_done = 0                 !! finished increments the XDMF file names
      real(dp), allocatable :: lambda_open(:)  !! load factors of the increment being written
      integer :: inc_open = 0
      type(reserve_t) :: reserve                    !! room for closing the file after a failure
      logical :: discard = .false.                  !! delete the file at close
                                                    !! (no room for the reserve)
   contains
      procedure :: create => results_create
      procedure :: write_run_info => results_run_info
      procedure :: write_contact_definition => results_contact_definition
      procedure :: write_increment => results_write_increment
      procedure :: set_status => results_set_status
      procedure :: close => results_close
      procedure :: is_open => results_is_open
      procedure :: increments_completed => results_increments_completed
      procedure :: write_cycles => results_write_cycles
      procedure :: write_summary => results_write_summary
      procedure :: write_header => results_write_header
   end type results_file_t

   logical :: library_open = .false.

   !> Size of the reserve file: room for what is written after a failure (the
   !! status, HDF5's last flush and close, the listing's closing lines).
   integer(i8), parameter :: RESERVE_BYTES = 1048576_i8
   !> Margin of a probe over the arrays of a group: object headers (about
   !! 1 kB a dataset), attributes, the growth of /increments' symbol table.
   integer(i8), parameter :: PROBE_MARGIN = 262144_i8
   !> The XDMF file is rewritten after every one of the first increments, then
   !! less often (see close_increment).
   integer, parameter :: XDMF_EVERY_UNTIL = 64

contains

   !> Create the file (truncating an old one) and write the mesh, with the
   !! Gauss-point layout of the body fields record (gp_start, xygp).
   subroutine results_create(this, path, m, body, status)
      class(results_file_t), intent(inout) :: this
      character(len=*), intent(in) :: path
      type(model_t), intent(in) :: m
      type(body_fields_t), intent(in) :: body
      type(status_t), intent(inout) :: status
      integer(hid_t) :: gid
      integer :: err, ie, k, n
      integer, allocatable :: conn(:, :), gel(:)

      ! a file object may be used again for another file
      call this%close()
      if (allocated(this%incs)) deallocate (this%incs)
      if (allocated(this%lambda)) deallocate (this%lambda)
      this%ncompleted = 0
      this%xdmf_done = 0
      this%nmixed = 0
      this%ncells = 0
      this%path = path
      if (.not. library_open) then
         call h5open_f(err)
         if (fail(err, 'initialise the HDF5 library')) return
         ! errors are reported by this module, not by HDF5's own error stack printer
         call h5eset_auto_f(0, err)
         library_open = .true.
      end if
      call h5fcreate_f(path, H5F_ACC_TRUNC_F, this%fid, err)
      if (e_fail(err, 'create the result file')) return
      this%opened = .true.
      this%discard = .false.
      call make_reserve(this, err)
      if (err /= 0) then
         ! no room even for the reserve: nothing of the run can be kept
         this%discard = .true.
         call status%set(STAT_IO, 'no room on the disk for '//path//'.reserve ('// &
                         itoa(int(RESERVE_BYTES))// &
                         ' bytes kept for closing the result file after a failure): is the disk &
                         &full?')
         return
      end if
      ! the mesh (coordinates, cells in three layouts, Gauss points)
      call probe_room(this, 8_i8*size(m%coord, kind=i8) + 4_i8*(2*MAX_NODE + 4)*m%nelem + &
                      28_i8*size(body%xygp, 2) &
                      + 4_i8*m%npoin, err)
      if (err /= 0) then
         call status%set(STAT_IO, 'no room on the disk for the mesh in '//path// &
                         ' (is the disk full?)')
         call results_set_status(this, 'failed at set-up: '//status%message)
         return
      end if
      call attr_string(this%fid, 'program', 'Kontakt2D', err)
      call attr_string(this%fid, 'version', K2D_VERSION, err)
      call attr_string(this%fid, 'title', m%title, err)
      call attr_string(this%fid, 'deck', m%deck_file, err)
      call attr_string(this%fid, 'analysis_type', ntype_name(m%ntype), err)
      call attr_int(this%fid, 'ntype', m%ntype, err)
      call attr_int(this%fid, 'ncase', m%ncase, err)
      call attr_string(this%fid, 'status', 'running', err)
      call attr_int(this%fid, 'increments_completed', 0, err)
      if (fail(err, 'write the file attributes')) return

      call h5gcreate_f(this%fid, 'mesh', gid, err)
      if (fail(err, 'create group /mesh')) return
      call write_real2(gid, 'coordinates', m%coord, err)
      allocate (conn(MAX_NODE, m%nelem))
      conn = m%lnods
      call write_int2(gid, 'connectivity', conn, err)
      call write_int1(gid, 'element_nodes', m%nnode_e, err)
      call write_int1(gid, 'material', m%matno, err)
      call write_real2(gid, 'gauss_coordinates', body%xygp, err)
      allocate (gel(size(body%xygp, 2)))
      n = 0
      do ie = 1, m%nelem
         do k = 1, body%gp_start(ie + 1) - body%gp_start(ie)
            n = n + 1
            gel(n) = ie
         end do
      end do
      call write_int1(gid, 'gauss_element', gel, err)
      if (fail(err, 'write the mesh')) return
      call write_xdmf_mesh(this, gid, m, err)
      if (fail(err, 'write the node tags and the 0-based cells of the mesh')) return
      call h5gclose_f(gid, err)
      call h5gcreate_f(this%fid, 'increments', gid, err)
      if (fail(err, 'create group /increments')) return
      call h5gclose_f(gid, err)
      call h5fflush_f(this%fid, H5F_SCOPE_GLOBAL_F, err)
      if (fail(err, 'flush the result file')) return
      allocate (this%incs(0), this%lambda(m%ncase, 0))
      call update_xdmf(this, status)
      if (.not. status%ok()) call results_set_status(this, 'failed at set-up: '//status%message)
   contains
      !> A failure of the library or of the file's creation (nothing written).
      logical function e_fail(e, what)
         integer, intent(in) :: e
         character(len=*), intent(in) :: what
         e_fail = e < 0
         if (e_fail) call status%set(STAT_IO, 'HDF5: cannot '//what//' ('//path//')')
      end function e_fail
      !> A failed write to the created file: the file says so, if it can.
      logical function fail(e, what)
         integer, intent(in) :: e
         character(len=*), intent(in) :: what
         fail = e < 0
         if (fail) then
            call status%set(STAT_IO, 'HDF5: cannot '//what//' ('//path//')')
            call results_set_status(this, 'failed at set-up: '//status%message)
         end if
      end function fail
   end subroutine results_create

   !> Hold the reserve file (see the module's notes); err = 0 when held.
   subroutine make_reserve(this, err)
      class(results_file_t), intent(inout) :: this
      integer, intent(out) :: err
      call this%reserve%hold(this%path//'.reserve', RESERVE_BYTES, err)
   end subroutine make_reserve

   !> Is there room on the disk for `nbytes` more (plus PROBE_MARGIN)?  err /= 0
   !! when there is not; the reserve is then released (disk_reserve).
   subroutine probe_room(this, nbytes, err)
      class(results_file_t), intent(inout) :: this
      integer(i8), intent(in) :: nbytes
      integer, intent(out) :: err
      call this%reserve%probe(nbytes + PROBE_MARGIN, err)
   end subroutine probe_room

   !> Delete the reserve file, if it is held.
   subroutine release_reserve(this)
      class(results_file_t), intent(inout) :: this
      call this%reserve%release()
   end subroutine release_reserve

   !> Group /increments/NNNNN of an accepted step: the step record's figures
   !! as attributes, the body fields and, for a contact model, the contact
   !! fields; then the step is recorded as completed and the file flushed.
   subroutine results_write_increment(this, step, body, status, contact)
      class(results_file_t), intent(inout) :: this
      type(step_record_t), intent(in) :: step
      type(body_fields_t), intent(in) :: body
      type(status_t), intent(inout) :: status
      type(contact_fields_t), intent(in), optional :: contact   !! written when step%contact
      integer(hid_t) :: gid
      integer :: err
      real(dp), allocatable :: u3(:, :)              !! the displacements with
                                                     !! a zero third component
      integer(i8) :: nbytes

      ! the body fields (displacement twice, stresses, reactions) and the contact fields
      nbytes = 8_i8*(size(body%disp, kind=i8)*5/2 + size(body%sig_nd, kind=i8) + &
                     size(body%sig_gp, kind=i8) &
                     + size(body%react, kind=i8) + size(body%gp_start, kind=i8)) + 512_i8*this%npair
      call probe_room(this, nbytes, err)
      if (err /= 0) then
         call status%set(STAT_IO, 'no room on the disk for the results of increment '// &
                         itoa(step%step)// &
                         ' (about '//itoa(int(nbytes/1024))//' kB) in '//this%path// &
                         ': is the disk full?')
         return
      end if
      call open_increment(this, step, gid, status)
      if (.not. status%ok()) return
      err = 0
      call write_real2(gid, 'displacement', body%disp, err)
      allocate (u3(3, size(body%disp, 2)))
      u3(1:2, :) = body%disp
      u3(3, :) = 0.0_dp
      call write_real2(gid, 'displacement_xyz', u3, err)
      call write_real2(gid, 'stress_nodal', body%sig_nd, err)
      call write_real2(gid, 'stress_gauss', body%sig_gp, err)
      call write_real2(gid, 'reaction', body%react, err)
      if (allocated(body%error_indicator)) then
         ! the a posteriori error estimate (module error_estimate): per element and of the model
         call write_real1(gid, 'error_indicator', body%error_indicator, err)
         call attr_real0(gid, 'estimated_error', body%estimated_error, err)
         call attr_real0(gid, 'energy_norm', body%energy_norm, err)
      end if
      if (step%contact) call attr_real0(gid, 'residual', step%residual, err)
      if (step%contact) call attr_real0(gid, 'law_drift', step%drift, err)
      if (step%contact) call attr_real0(gid, 'law_drift_tangential', step%drift_t, err)
      if (step%ideal) call attr_real0(gid, 'penetration', step%penetration, err)
      if (step%ideal) call attr_int(gid, 'augmentations', step%augmentations, err)
      if (allocated(step%pretension_force)) then
         ! pretension sections, in the order of their cards: the force across each (tension
         ! positive, from the elements' internal forces at the cut) and its shortening
         call attr_real1(gid, 'pretension_force', step%pretension_force, err)
         call attr_real1(gid, 'pretension_shortening', step%pretension_shortening, err)
      end if
      call attr_real0(gid, 'imbalance', step%imbalance, err)
      call attr_real0(gid, 'imbalance_limit', step%imbalance_limit, err)
      call attr_int(gid, 'invariant_violations', step%violations, err)
      if (allocated(step%doubts)) then
         if (len(step%doubts) > 0) call attr_string(gid, 'doubts', step%doubts, err)
      end if
      if (allocated(step%warnings)) then
         if (len(step%warnings) > 0) call attr_string(gid, 'warnings', step%warnings, err)
      end if
      call attr_int(gid, 'deck_increment', step%deck_increment, err)
      call attr_real0(gid, 'deck_increment_fraction', step%fraction, err)
      call attr_int(gid, 'cuts', step%cuts, err)
      if (err < 0) then
         call status%set(STAT_IO, 'HDF5: cannot write the results of increment '//itoa(step%step))
      end if
      if (step%contact .and. present(contact) .and. status%ok()) then
         call write_contact_fields(gid, contact, status)
      end if
      ! `converged` last: a group that a failed write left incomplete is never marked converged
      if (status%ok()) then
         call attr_int(gid, 'converged', merge(1, 0, step%converged), err)
         if (err < 0) then
            call status%set(STAT_IO, 'HDF5: cannot write attributes of increment '//itoa(step%step))
         end if
      end if
      if (.not. status%ok()) then
         call drop_increment(this, gid)
         return
      end if
      call close_increment(this, gid, status)
   end subroutine results_write_increment

   !> Create the group of a step with its first attributes; return its id.
   subroutine open_increment(this, step, gid, status)
      class(results_file_t), intent(inout) :: this
      type(step_record_t), intent(in) :: step
      integer(hid_t), intent(out) :: gid
      type(status_t), intent(inout) :: status
      integer :: err
      character(len=16) :: name

      write (name, '(i5.5)') step%step
      this%inc_open = step%step
      this%lambda_open = step%lambda
      call h5gcreate_f(this%fid, 'increments/'//trim(name), gid, err)
      if (err < 0) then
         call status%set(STAT_IO, 'HDF5: cannot create group /increments/'//trim(name)//' in '// &
                         this%path)
         return
      end if
      call attr_int(gid, 'increment', step%step, err)
      call attr_real1(gid, 'load_factor', step%lambda, err)
      call attr_int(gid, 'iterations', step%solutions, err)
      call attr_int(gid, 'repeats', step%repeats, err)
      if (err < 0) then
         call status%set(STAT_IO, 'HDF5: cannot write attributes of increment '//itoa(step%step))
      end if
   end subroutine open_increment

   !> A group that a failed write left incomplete: closed and unlinked, so
   !! that the file lists only complete increments (its space is lost).
   subroutine drop_increment(this, gid)
      class(results_file_t), intent(inout) :: this
      integer(hid_t), intent(in) :: gid
      integer :: e
      call h5gclose_f(gid, e)
      call h5ldelete_f(this%fid, 'increments/'//group_name(this%inc_open), e)
   end subroutine drop_increment

   !> Name of the group of step n (NNNNN).
   pure function group_name(n) result(name)
      integer, intent(in) :: n
      character(len=5) :: name
      write (name, '(i5.5)') n
   end function group_name

   !> Close an increment group, record it as completed and flush the file:
   !! the group is flushed first and counted only then, so that
   !! increments_completed never counts a group that did not reach the disk.
   subroutine close_increment(this, gid, status)
      class(results_file_t), intent(inout) :: this
      integer(hid_t), intent(in) :: gid
      type(status_t), intent(inout) :: status
      integer :: err, e
      err = 0
      call h5gclose_f(gid, e)
      call keep(e, err)
      call h5fflush_f(this%fid, H5F_SCOPE_GLOBAL_F, e)
      call keep(e, err)
      if (err < 0) then
         call status%set(STAT_IO, 'HDF5: cannot write increment '//itoa(this%inc_open)//' to '// &
                         this%path// &
                         ' (close its group, flush the file: is the disk full?)')
         call h5ldelete_f(this%fid, 'increments/'//group_name(this%inc_open), e)
         return
      end if
      this%ncompleted = this%ncompleted + 1
      call h5adelete_f(this%fid, 'increments_completed', e)
      call keep(e, err)
      call attr_int(this%fid, 'increments_completed', this%ncompleted, err)
      call h5fflush_f(this%fid, H5F_SCOPE_GLOBAL_F, e)
      call keep(e, err)
      if (err < 0) then
         call status%set(STAT_IO, 'HDF5: cannot record increment '//itoa(this%inc_open)// &
                         ' as completed (update increments_completed, flush) in '//this%path// &
                         ' (is the disk full?)')
         return
      end if
      if (allocated(this%incs)) then
         if (this%ncompleted > size(this%incs)) then
            block
               integer, allocatable :: ti(:)
               real(dp), allocatable :: t(:, :)
               allocate (ti(2*size(this%incs) + 16), &
                         t(size(this%lambda, 1), 2*size(this%incs) + 16))
               ti(1:this%ncompleted - 1) = this%incs(1:this%ncompleted - 1)
               t(:, 1:this%ncompleted - 1) = this%lambda(:, 1:this%ncompleted - 1)
               call move_alloc(ti, this%incs)
               call move_alloc(t, this%lambda)
            end block
         end if
         this%incs(this%ncompleted) = this%inc_open
         this%lambda(:, this%ncompleted) = this%lambda_open(1:size(this%lambda, 1))
         ! the XDMF file is rewritten whole: after each of the first XDMF_EVERY_UNTIL
         ! increments, then when the count has grown by an eighth (linear time in
         ! all), and at the end of the run (set_status)
         if (this%ncompleted <= XDMF_EVERY_UNTIL .or. this%ncompleted - this%xdmf_done >= &
               this%xdmf_done/8) then
            call update_xdmf(this, status)
         end if
      end if
   end subroutine close_increment

   !> Mesh datasets for the XDMF sidecar: /mesh/node_tags (gmsh tags, or the
   !! deck's node numbers), 0-based connectivity per element kind
   !! (/mesh/cells_tri3, cells_quad4, cells_quad8, cells_quad9, only the kinds
   !! present) and, for a mixed mesh, /mesh/cells_mixed (XDMF Mixed topology).
   subroutine write_xdmf_mesh(this, gid, m, err)
      class(results_file_t), intent(inout) :: this
      integer(hid_t), intent(in) :: gid
      type(model_t), intent(in) :: m
      integer, intent(inout) :: err
      integer, allocatable :: tags(:), cells(:, :), mixed(:)
      integer :: k, ie, n, ip, pos
      character(len=5), parameter :: names(4) = ['tri3 ', 'quad4', 'quad8', 'quad9']

      this%npoin = m%npoin
      allocate (tags(m%npoin))
      if (allocated(m%node_tag)) then
         tags(:) = m%node_tag
      else
         tags(:) = [(ip, ip=1, m%npoin)]
      end if
      call write_int1(gid, 'node_tags', tags, err)
      do k = 1, 4
         this%ncells(k) = count(m%nnode_e(1:m%nelem) == CELL_NNODE(k))
         if (this%ncells(k) == 0) cycle
         allocate (cells(CELL_NNODE(k), this%ncells(k)))
         n = 0
         do ie = 1, m%nelem
            if (m%nnode_e(ie) /= CELL_NNODE(k)) cycle
            n = n + 1
            cells(:, n) = m%lnods(1:CELL_NNODE(k), ie) - 1
         end do
         call write_int2(gid, 'cells_'//trim(names(k)), cells, err)
         deallocate (cells)
      end do
      if (count(this%ncells > 0) > 1) then
         this%nmixed = m%nelem + sum(m%nnode_e(1:m%nelem))
         allocate (mixed(this%nmixed))
         pos = 0
         do ie = 1, m%nelem
            do k = 1, 4
               if (m%nnode_e(ie) == CELL_NNODE(k)) mixed(pos + 1) = XDMF_CELL_CODE(k)
            end do
            mixed(pos + 2:pos + 1 + m%nnode_e(ie)) = m%lnods(1:m%nnode_e(ie), ie) - 1
            pos = pos + 1 + m%nnode_e(ie)
         end do
         call write_int1(gid, 'cells_mixed', mixed, err)
      end if
   end subroutine write_xdmf_mesh

   !> Rewrite the XDMF sidecar for the increments finished so far.
   subroutine update_xdmf(this, status)
      class(results_file_t), intent(inout) :: this
      type(status_t), intent(inout) :: status
      integer :: ierr
      call write_xdmf(xdmf_path(this%path), this%path, this%npoin, this%ncells, this%nmixed, &
                      this%incs(1:this%ncompleted), this%lambda(:, 1:this%ncompleted), ierr, &
                      this%npair)
      if (ierr /= 0) then
         call status%set(STAT_IO, 'cannot write the XDMF file '//xdmf_path(this%path)// &
                         ' (error '//itoa(ierr)//')')
      else
         this%xdmf_done = this%ncompleted
      end if
   end subroutine update_xdmf

   !> Replace the root attribute `status` (running, completed, failed: ...).
   !! A failure is returned in `status` when it is given (and ok so far).
   subroutine results_set_status(this, text, status)
      class(results_file_t), intent(inout) :: this
      character(len=*), intent(in) :: text
      type(status_t), intent(inout), optional :: status
      integer :: err, e
      if (.not. this%opened) return
      ! the end of the run: the reserve gives the status its room
      call release_reserve(this)
      ! the XDMF file names every finished increment
      if (allocated(this%incs) .and. this%xdmf_done < this%ncompleted) then
         if (present(status)) then
            call update_xdmf(this, status)
         else
            block
               type(status_t) :: ignored
               call update_xdmf(this, ignored)
            end block
         end if
      end if
      err = 0
      call h5adelete_f(this%fid, 'status', e)
      call keep(e, err)
      call attr_string(this%fid, 'status', text, err)
      call h5fflush_f(this%fid, H5F_SCOPE_GLOBAL_F, e)
      call keep(e, err)
      if (err < 0 .and. present(status)) then
         if (status%ok()) call status%set(STAT_IO, &
                                          'HDF5: cannot write the status of the run to '// &
                                          this%path// &
                                          ' (is the disk full?)')
      end if
   end subroutine results_set_status

   !> Close the file.  When HDF5 cannot (it cannot flush: a full disk), the
   !! failure is returned in `status` when it is given (and ok so far), and
   !! the process will end without HDF5's clean-up at exit, which would try
   !! the same close again and crash inside the library (errors%skip_exit_handlers).
   subroutine results_close(this, status)
      class(results_file_t), intent(inout) :: this
      type(status_t), intent(inout), optional :: status
      integer :: err, u, e
      if (.not. this%opened) return
      call release_reserve(this)
      call h5fclose_f(this%fid, err)
      this%opened = .false.
      if (this%discard) then
         ! not even the reserve could be written: no result file
         open (newunit=u, file=this%path, status='old', action='readwrite', iostat=e)
         if (e == 0) close (u, status='delete', iostat=e)
         if (err < 0) call skip_exit_handlers()
         return
      end if
      if (err < 0) then
         call skip_exit_handlers()
         if (present(status)) then
            if (status%ok()) then
               call status%set(STAT_IO, 'HDF5: cannot close '//this%path//' (is the disk full?)')
            end if
         end if
      end if
   end subroutine results_close

   !> Is the file open (created and not yet closed)?
   pure logical function results_is_open(this) result(yes)
      class(results_file_t), intent(in) :: this
      yes = this%opened
   end function results_is_open

   !> Increments recorded as completed so far.
   pure integer function results_increments_completed(this) result(n)
      class(results_file_t), intent(in) :: this
      n = this%ncompleted
   end function results_increments_completed

   !> /cycles: the load cycles of a periodic history (records' cycle_table_t; shapes as seen
   !! from C/Python): first_increment, last_increment (ncycle) and energy, force_amplitude,
   !! slip_amplitude, secant_stiffness, loss_factor, damping_ratio (ncycle, ninterface).
   !! Written once, at the end of the run.
   subroutine results_write_cycles(this, tab, status)
      class(results_file_t), intent(inout) :: this
      type(cycle_table_t), intent(in) :: tab
      type(status_t), intent(inout) :: status
      integer(hid_t) :: gid
      integer :: err, e
      if (.not. this%opened .or. tab%ncycle <= 0) return
      err = 0
      call h5gcreate_f(this%fid, 'cycles', gid, e)
      if (e < 0) then
         call status%set(STAT_IO, 'HDF5: cannot create group /cycles in '//this%path)
         return
      end if
      call write_int1(gid, 'first_increment', tab%first, err)
      call write_int1(gid, 'last_increment', tab%last, err)
      call write_real2(gid, 'energy', tab%energy, err)
      call write_real2(gid, 'force_amplitude', tab%force_amplitude, err)
      call write_real2(gid, 'slip_amplitude', tab%slip_amplitude, err)
      call write_real2(gid, 'secant_stiffness', tab%secant_stiffness, err)
      call write_real2(gid, 'loss_factor', tab%loss_factor, err)
      call write_real2(gid, 'damping_ratio', tab%damping_ratio, err)
      if (allocated(tab%ratios_defined)) then
         call write_int2(gid, 'ratios_defined', merge(1, 0, tab%ratios_defined), err)
      end if
      call h5gclose_f(gid, e)
      call keep(e, err)
      call h5fflush_f(this%fid, H5F_SCOPE_GLOBAL_F, e)
      call keep(e, err)
      if (err < 0) call status%set(STAT_IO, 'HDF5: cannot write /cycles in '//this%path)
   end subroutine results_write_cycles

   !> Root attributes of the figures of the listing's header not written elsewhere: the counts
   !! (materials, deck increments, equations, restrained dofs) and what the equation numbering
   !! did (why its order; the profile in the user's order and in the order used: skyline
   !! length, mean and largest column height).
   subroutine results_write_header(this, m, info, numbering, status)
      class(results_file_t), intent(inout) :: this
      type(model_t), intent(in) :: m
      type(run_info_t), intent(in) :: info
      type(numbering_report_t), intent(in) :: numbering
      type(status_t), intent(inout) :: status
      integer :: err
      if (.not. this%opened) return
      err = 0
      call attr_int(this%fid, 'materials', m%nmats, err)
      call attr_int(this%fid, 'deck_increments', m%nincs, err)
      call attr_int(this%fid, 'equations', info%neq, err)
      call attr_int(this%fid, 'restrained_dofs', info%nres, err)
      if (allocated(numbering%reason)) then
         if (len(numbering%reason) > 0) then
            call attr_string(this%fid, 'ordering_reason', numbering%reason, err)
         end if
      end if
      call attr_real1(this%fid, 'profile_user_order', [real(numbering%profile_before, dp), &
                      numbering%mean_before, real(numbering%max_before, dp)], err)
      call attr_real1(this%fid, 'profile_used', [real(numbering%profile_after, dp), &
                      numbering%mean_after, real(numbering%max_after, dp)], err)
      if (err < 0) call status%set(STAT_IO, 'HDF5: cannot write the header attributes to '// &
                                   this%path)
   end subroutine results_write_header

   !> /summary: the closing summary of the run as the listing and the terminal print it
   !! (run_summary_t, docs/results-format.md "Run summary"): the load stages, the interface at the
   !! end, the error estimate, the energy dissipated, the pretension sections, the doubts, the
   !! solutions and the time.  Written once, at the end of a run that got past its set-up.
   subroutine results_write_summary(this, s, status)
      class(results_file_t), intent(inout) :: this
      type(run_summary_t), intent(in) :: s
      type(status_t), intent(inout) :: status
      integer(hid_t) :: gid
      integer :: err, e
      if (.not. this%opened) return
      ! the end of the run: the reserve (1 MB) gives the summary (a few kB, 56 bytes a load stage)
      ! and then the status their room, whatever the listing took meanwhile
      call release_reserve(this)
      err = 0
      call h5gcreate_f(this%fid, 'summary', gid, e)
      if (e < 0) then
         call status%set(STAT_IO, 'HDF5: cannot create group /summary in '//this%path)
         return
      end if
      call attr_int(gid, 'increments', s%nstep, err)
      call attr_int(gid, 'solutions', s%solutions_total, err)
      call attr_real0(gid, 'wall_seconds', s%seconds, err)
      call attr_int(gid, 'warnings', s%warnings, err)
      ! the load stages (by the factor of one load case)
      call attr_int(gid, 'stage_load_case', s%icase, err)
      call attr_int(gid, 'stages_by_deck', merge(1, 0, s%by_deck), err)
      if (size(s%first) > 0) then
         call write_int1(gid, 'stage_first_increment', s%first, err)
         call write_int1(gid, 'stage_last_increment', s%last, err)
         call write_int1(gid, 'stage_direction', s%direction, err)
         call write_real1(gid, 'stage_load_from', s%lam_from, err)
         call write_real1(gid, 'stage_load_to', s%lam_to, err)
         call write_int1(gid, 'stage_solutions', s%solutions, err)
         call write_real1(gid, 'stage_law_drift', s%drift, err)
      end if
      if (s%contact) call summary_interface(gid, s, err)
      if (s%estimated) then
         call attr_real0(gid, 'estimated_error', s%estimated_error, err)
         if (allocated(s%zone_width)) then
            call attr_real1(gid, 'zone_width', s%zone_width, err)
            call attr_int1(gid, 'zone_pairs', s%zone_pairs, err)
            call attr_real1(gid, 'zone_jump', s%zone_jump, err)
         end if
         if (s%peak_step > 0) then
            ! the estimate at the largest strain energy (the run ended below half of it)
            call attr_int(gid, 'peak_estimate_increment', s%peak_step, err)
            call attr_real0(gid, 'peak_estimated_error', s%peak_error, err)
            call attr_real0(gid, 'peak_energy_ratio', s%peak_energy_ratio, err)
            if (allocated(s%peak_zone_width)) then
               call attr_real1(gid, 'peak_zone_width', s%peak_zone_width, err)
               call attr_int1(gid, 'peak_zone_pairs', s%peak_zone_pairs, err)
               call attr_real1(gid, 'peak_zone_jump', s%peak_zone_jump, err)
            end if
         end if
      end if
      if (allocated(s%dissipated)) then
         call attr_real1(gid, 'dissipated_energy', s%dissipated, err)
         call attr_real1(gid, 'dissipated_normal', s%dissipated_normal, err)
         call attr_real1(gid, 'dissipated_tangential', s%dissipated_tangential, err)
      end if
      if (s%pretension_step > 0) then
         call attr_int(gid, 'pretension_increment', s%pretension_step, err)
         call attr_real1(gid, 'pretension_force', s%pretension_force, err)
         call attr_real1(gid, 'pretension_shortening', s%pretension_shortening, err)
      end if
      call attr_int(gid, 'doubtful_increments', s%doubtful, err)
      if (s%doubtful > 0) then
         call attr_int(gid, 'doubtful_frozen', s%doubt_frozen, err)
         call attr_int(gid, 'doubtful_drift', s%doubt_drift, err)
         call attr_int(gid, 'doubtful_violations', s%doubt_violations, err)
         call attr_int(gid, 'first_doubtful_increment', s%first_doubtful, err)
         if (len(s%doubts) > 0) call attr_string(gid, 'doubts', s%doubts, err)
         if (len(s%doubt_details) > 0) call attr_string(gid, 'doubt_details', s%doubt_details, err)
      end if
      call h5gclose_f(gid, e)
      call keep(e, err)
      call h5fflush_f(this%fid, H5F_SCOPE_GLOBAL_F, e)
      call keep(e, err)
      if (err < 0) call status%set(STAT_IO, 'HDF5: cannot write /summary in '//this%path)
   end subroutine results_write_summary

   !> The interface at the end of the run, attributes of /summary (model units; their names in
   !! length_unit, stress_unit, force_unit as the listing prints them).
   subroutine summary_interface(gid, s, err)
      integer(hid_t), intent(in) :: gid
      type(run_summary_t), intent(in) :: s
      integer, intent(inout) :: err
      call attr_string(gid, 'length_unit', s%length_unit, err)
      call attr_string(gid, 'stress_unit', s%stress_unit, err)
      call attr_string(gid, 'force_unit', s%force_unit, err)
      call attr_int(gid, 'pairs', s%npair, err)
      call attr_int(gid, 'closed_pairs', s%nclosed, err)
      call attr_int(gid, 'slipping_pairs', s%nslip, err)
      call attr_int(gid, 'peak_pair', s%peak_pair, err)
      call attr_real0(gid, 'peak_pressure', s%peak_pressure, err)
      call attr_real1(gid, 'peak_position', s%peak_xy, err)
      call attr_real0(gid, 'contact_width', s%width, err)
      call attr_real0(gid, 'contact_area', s%area, err)
      call attr_real0(gid, 'approach', s%approach, err)
      call attr_real0(gid, 'force_normal', s%force_n, err)
      call attr_real0(gid, 'force_tangential', s%force_t, err)
      if (s%niface > 0) then                        ! the same per interface of the deck
         call attr_int1(gid, 'interface_pairs', s%if_pairs, err)
         call attr_int1(gid, 'interface_closed_pairs', s%if_closed, err)
         call attr_int1(gid, 'interface_slipping_pairs', s%if_slip, err)
         call attr_int1(gid, 'interface_peak_pair', s%if_peak_pair, err)
         call attr_real1(gid, 'interface_peak_pressure', s%if_peak, err)
         call attr_real1(gid, 'interface_peak_x', s%if_peak_x, err)
         call attr_real1(gid, 'interface_peak_y', s%if_peak_y, err)
         call attr_real1(gid, 'interface_contact_width', s%if_width, err)
         call attr_real1(gid, 'interface_contact_area', s%if_area, err)
         call attr_real1(gid, 'interface_approach', s%if_approach, err)
         call attr_real1(gid, 'interface_force_normal', s%if_force_n, err)
         call attr_real1(gid, 'interface_force_tangential', s%if_force_t, err)
      end if
      call attr_int(gid, 'unloaded_pairs', s%nunloaded, err)
      if (s%unloaded) call attr_real0(gid, 'residual_closure', s%residual_closure, err)
      call attr_int(gid, 'beyond_range_pairs', s%nbeyond, err)
      if (s%nbeyond > 0) then
         call attr_int(gid, 'beyond_range_pair', s%beyond_pair, err)
         call attr_real0(gid, 'beyond_range_reversal_pressure', s%beyond_pa, err)
         call attr_real0(gid, 'beyond_range_p_star', s%beyond_pstar, err)
      end if
      call attr_real0(gid, 'worst_law_drift', s%worst_drift, err)
      call attr_int(gid, 'worst_law_drift_increment', s%worst_drift_step, err)
   end subroutine summary_interface

   !> Root attributes of the run: its plan (the solver, who chose it and
   !! why, the contact system, the order of the equations, the contact
   !! scheme), the bounds of the automatic increments (with the increments'
   !! `cuts` their history), whether the bodies were condensed onto the
   !! contact equations and, for a contact model, the cap on solutions per
   !! increment the run used.
   subroutine results_run_info(this, info, status)
      class(results_file_t), intent(inout) :: this
      type(run_info_t), intent(in) :: info
      type(status_t), intent(inout) :: status
      integer :: err
      err = 0
      associate (p => info%plan)
         call attr_string(this%fid, 'solver', solver_name(p%solver), err)
         call attr_string(this%fid, 'solver_choice', choice_name(p%solver_choice), err)
         if (p%solver_choice == CHOICE_AUTOMATIC .and. allocated(p%solver_reason)) then
            call attr_string(this%fid, 'solver_reason', p%solver_reason, err)
         end if
         call attr_string(this%fid, 'contact_system', system_name(p%contact_system), err)
         call attr_string(this%fid, 'ordering', ordering_name(p%ordering), err)
         call attr_string(this%fid, 'scheme', scheme_name(p%scheme), err)
      end associate
      call attr_int(this%fid, 'autoinc', merge(1, 0, info%autoinc), err)
      call attr_real0(this%fid, 'autoinc_min_fraction', info%autoinc_min, err)
      call attr_int(this%fid, 'autoinc_easy_solutions', info%autoinc_easy, err)
      call attr_int(this%fid, 'condensed', merge(1, 0, info%condensed), err)
      if (info%npair > 0) call attr_int(this%fid, 'max_repeats', info%max_repeats, err)
      if (err < 0) call status%set(STAT_IO, 'HDF5: cannot write the run attributes')
   end subroutine results_run_info

   !> /contact: the pairs and the interface laws (written once); the cap on
   !! solutions per increment as the run uses it (run information).
   subroutine results_contact_definition(this, c, info, status)
      class(results_file_t), intent(inout) :: this
      type(contact_def_t), intent(in) :: c
      type(run_info_t), intent(in) :: info
      type(status_t), intent(inout) :: status
      integer(hid_t) :: gid, iid
      integer :: err, np, i, e
      real(dp), allocatable :: v2(:, :), wm(:, :)
      integer, allocatable :: nm(:, :)
      character(len=16) :: name
      err = 0
      np = size(c%pairs)
      this%npair = np
      call probe_room(this, 256_i8*np + 1024_i8*size(c%ifaces), e)
      if (e /= 0) then
         call status%set(STAT_IO, 'no room on the disk for the contact definition in '// &
                         this%path// &
                         ' (is the disk full?)')
         call results_set_status(this, 'failed at set-up: '//status%message)
         return
      end if
      call h5gcreate_f(this%fid, 'contact', gid, e)
      if (e < 0) then
         call status%set(STAT_IO, 'HDF5: cannot create group /contact in '//this%path)
         return
      end if
      call write_int1(gid, 'node_a', c%pairs%node_a, err)
      call write_int1(gid, 'node_b', c%pairs%node_b, err)
      call write_int1(gid, 'interface', c%pairs%iface, err)
      allocate (v2(2, np))
      do i = 1, np
         v2(:, i) = c%pairs(i)%position
      end do
      call write_real2(gid, 'position', v2, err)
      do i = 1, np
         v2(:, i) = c%pairs(i)%n
      end do
      call write_real2(gid, 'normal', v2, err)
      do i = 1, np
         v2(:, i) = c%pairs(i)%t
      end do
      call write_real2(gid, 'tangent', v2, err)
      call write_real1(gid, 'gap', c%pairs%g0, err)
      call write_real1(gid, 'area', c%pairs%area, err)
      ! the master side of every pair: kind, nodes and weights (u_b = sum w u)
      call write_int1(gid, 'kind', c%pairs%kind, err)
      allocate (nm(MAX_PAIR_NODES - 1, np), wm(MAX_PAIR_NODES - 1, np))
      do i = 1, np
         nm(:, i) = c%pairs(i)%nodes(2:)
         wm(:, i) = c%pairs(i)%w(2:)
         nm(c%pairs(i)%nn:, i) = 0
         wm(c%pairs(i)%nn:, i) = 0.0_dp
      end do
      call write_int2(gid, 'master_nodes', nm, err)
      call write_real2(gid, 'master_weights', wm, err)
      call attr_string(gid, 'update', update_name(c%opts%update), err)
      call attr_int(gid, 'max_repeats', info%max_repeats, err)
      call attr_int(gid, 'max_switch', info%max_switch, err)
      call attr_real1(gid, 'augmented', [c%opts%aug_factor, c%opts%aug_tol], err)
      do i = 1, size(c%ifaces)
         write (name, '(a,i0)') 'interface_', i
         call h5gcreate_f(gid, trim(name), iid, e)
         if (e < 0) err = e
         associate (f => c%ifaces(i))
            call attr_string(iid, 'law', law_name(f%law), err)
            call attr_string(iid, 'matching', matching_name(f%matching, f%rigid), err)
            call attr_int(iid, 'sides_swapped', merge(1, 0, f%sides_swapped), err)
            if (f%rigid > 0) then
               associate (rb => c%rigids(f%rigid))
                  call attr_string(iid, 'rigid_shape', rigid_shape_name(rb%shape), err)
                  call attr_int(iid, 'rigid_node', rb%node, err)
                  if (allocated(rb%xy)) then
                     if (size(rb%xy, 2) > 0) call write_real2(iid, 'rigid_profile', rb%xy, err)
                  end if
                  call attr_real1(iid, 'rigid_circle', [rb%centre, rb%radius], err)
               end associate
            end if
            call attr_string(iid, 'units', units_name(f%units), err)
            call attr_real1(iid, 'normal_input', [f%cn_in, f%m_in, f%cn2_in, f%m2_in], err)
            call attr_real1(iid, 'normal_model', [f%cn, f%m, f%cn2, f%m2], err)
            call attr_real1(iid, 'tangent_s', [f%s], err)
            call attr_string(iid, 'friction', friction_name(f%friction), err)
            call attr_real1(iid, 'friction_parameters', [f%mu_m, f%beta, f%n_hard], err)
            call attr_int(iid, 'hardening', merge(1, 0, f%hardening), err)
            call attr_real1(iid, 'kappa', [f%kappa], err)
            call attr_string(iid, 'effective_slip', slip_name(f%slip_def), err)
            if (allocated(f%r_t)) call write_real1(iid, 'r_model', f%r_t, err)
         end associate
         call h5gclose_f(iid, e)
      end do
      call h5gclose_f(gid, e)
      if (err < 0) call status%set(STAT_IO, 'HDF5: cannot write /contact in '//this%path)
   end subroutine results_contact_definition

   !> Group `contact` of an increment: the contact fields record (see
   !! docs/results-format.md).
   subroutine write_contact_fields(gid, cf, status)
      integer(hid_t), intent(in) :: gid
      type(contact_fields_t), intent(in) :: cf
      type(status_t), intent(inout) :: status
      integer(hid_t) :: cid
      integer :: err, e
      err = 0
      call h5gcreate_f(gid, 'contact', cid, e)
      if (e < 0) then
         call status%set(STAT_IO, 'HDF5: cannot create a contact group')
         return
      end if
      call write_real1(cid, 'pressure', cf%pressure, err)
      call write_real1(cid, 'shear', cf%shear, err)
      call write_real1(cid, 'force_normal', cf%force_normal, err)
      call write_real1(cid, 'force_tangential', cf%force_tangential, err)
      call write_real1(cid, 'closure', cf%closure, err)
      call write_real1(cid, 'slip', cf%slip, err)
      call write_real1(cid, 'slip_irreversible', cf%slip_irreversible, err)
      call write_real1(cid, 'slip_gross', cf%slip_gross, err)
      call write_real1(cid, 'effective_slip', cf%effective_slip, err)
      call write_real1(cid, 'friction', cf%friction, err)
      call write_int1(cid, 'normal_state', cf%normal_state, err)
      call write_int1(cid, 'tangential_state', cf%tangential_state, err)
      call write_real1(cid, 'stiffness_normal', cf%stiffness_normal, err)
      call write_real1(cid, 'stiffness_tangential', cf%stiffness_tangential, err)
      if (allocated(cf%switches)) call write_int1(cid, 'switches', cf%switches, err)
      if (allocated(cf%resolution)) then
         ! how well the pairs resolve the pressure (module error_estimate); the zone of each
         ! interface as attributes (the datasets are per pair)
         call write_real1(cid, 'resolution', cf%resolution, err)
         call attr_real1(cid, 'zone_width', cf%zone_width, err)
         call attr_int1(cid, 'zone_pairs', cf%zone_pairs, err)
      end if
      if (allocated(cf%dissipation_tangential)) then
         ! the energy dissipated by the contact laws (module contact_energy): per pair, and per
         ! interface as attributes
         call write_real1(cid, 'dissipation_tangential', cf%dissipation_tangential, err)
         call write_real1(cid, 'dissipation_normal', cf%dissipation_normal, err)
         call attr_real1(cid, 'dissipated_energy', cf%dissipated_energy, err)
         call attr_real1(cid, 'dissipated_increment', cf%dissipated_increment, err)
         call attr_real1(cid, 'tangential_force_total', cf%tangential_force_total, err)
         call attr_real1(cid, 'slip_mean', cf%slip_mean, err)
      end if
      call h5gclose_f(cid, e)
      if (err < 0) call status%set(STAT_IO, 'HDF5: cannot write the contact results')
   end subroutine write_contact_fields

   ! ------------------------------------------------------------------ helpers
   ! Each helper leaves err < 0 if any HDF5 call failed (errors accumulate).

   subroutine write_real2(loc, name, a, err)
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      real(dp), intent(in) :: a(:, :)
      integer, intent(inout) :: err
      integer(hid_t) :: sid, did
      integer(hsize_t) :: dims(2)
      integer :: e
      dims = [size(a, 1, kind=hsize_t), size(a, 2, kind=hsize_t)]
      call h5screate_simple_f(2, dims, sid, e)
      call keep(e, err)
      call h5dcreate_f(loc, name, H5T_NATIVE_DOUBLE, sid, did, e)
      call keep(e, err)
      if (e >= 0) then
         call h5dwrite_f(did, H5T_NATIVE_DOUBLE, real(a, c_double), dims, e)
         call keep(e, err)
         call h5dclose_f(did, e)
      end if
      call h5sclose_f(sid, e)
   end subroutine write_real2

   subroutine write_real1(loc, name, a, err)
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      real(dp), intent(in) :: a(:)
      integer, intent(inout) :: err
      integer(hid_t) :: sid, did
      integer(hsize_t) :: dims(1)
      integer :: e
      dims = [size(a, kind=hsize_t)]
      call h5screate_simple_f(1, dims, sid, e)
      call keep(e, err)
      call h5dcreate_f(loc, name, H5T_NATIVE_DOUBLE, sid, did, e)
      call keep(e, err)
      if (e >= 0) then
         call h5dwrite_f(did, H5T_NATIVE_DOUBLE, real(a, c_double), dims, e)
         call keep(e, err)
         call h5dclose_f(did, e)
      end if
      call h5sclose_f(sid, e)
   end subroutine write_real1

   subroutine write_int1(loc, name, a, err)
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      integer, intent(in) :: a(:)
      integer, intent(inout) :: err
      integer(hid_t) :: sid, did
      integer(hsize_t) :: dims(1)
      integer :: e
      dims = [size(a, kind=hsize_t)]
      call h5screate_simple_f(1, dims, sid, e)
      call keep(e, err)
      call h5dcreate_f(loc, name, H5T_NATIVE_INTEGER, sid, did, e)
      call keep(e, err)
      if (e >= 0) then
         call h5dwrite_f(did, H5T_NATIVE_INTEGER, a, dims, e)
         call keep(e, err)
         call h5dclose_f(did, e)
      end if
      call h5sclose_f(sid, e)
   end subroutine write_int1

   subroutine write_int2(loc, name, a, err)
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      integer, intent(in) :: a(:, :)
      integer, intent(inout) :: err
      integer(hid_t) :: sid, did
      integer(hsize_t) :: dims(2)
      integer :: e
      dims = [size(a, 1, kind=hsize_t), size(a, 2, kind=hsize_t)]
      call h5screate_simple_f(2, dims, sid, e)
      call keep(e, err)
      call h5dcreate_f(loc, name, H5T_NATIVE_INTEGER, sid, did, e)
      call keep(e, err)
      if (e >= 0) then
         call h5dwrite_f(did, H5T_NATIVE_INTEGER, a, dims, e)
         call keep(e, err)
         call h5dclose_f(did, e)
      end if
      call h5sclose_f(sid, e)
   end subroutine write_int2

   subroutine attr_int(loc, name, v, err)
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      integer, intent(in) :: v
      integer, intent(inout) :: err
      integer(hid_t) :: sid, aid
      integer(hsize_t), parameter :: dims(1) = [1]
      integer :: e
      call h5screate_f(H5S_SCALAR_F, sid, e)
      call keep(e, err)
      call h5acreate_f(loc, name, H5T_NATIVE_INTEGER, sid, aid, e)
      call keep(e, err)
      if (e >= 0) then
         call h5awrite_f(aid, H5T_NATIVE_INTEGER, v, dims, e)
         call keep(e, err)
         call h5aclose_f(aid, e)
      end if
      call h5sclose_f(sid, e)
   end subroutine attr_int

   subroutine attr_int1(loc, name, v, err)
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      integer, intent(in) :: v(:)
      integer, intent(inout) :: err
      integer(hid_t) :: sid, aid
      integer(hsize_t) :: dims(1)
      integer :: e
      dims = [size(v, kind=hsize_t)]
      call h5screate_simple_f(1, dims, sid, e)
      call keep(e, err)
      call h5acreate_f(loc, name, H5T_NATIVE_INTEGER, sid, aid, e)
      call keep(e, err)
      if (e >= 0) then
         call h5awrite_f(aid, H5T_NATIVE_INTEGER, v, dims, e)
         call keep(e, err)
         call h5aclose_f(aid, e)
      end if
      call h5sclose_f(sid, e)
   end subroutine attr_int1

   subroutine attr_real0(loc, name, v, err)
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      real(dp), intent(in) :: v
      integer, intent(inout) :: err
      call attr_real1(loc, name, [v], err)
   end subroutine attr_real0

   subroutine attr_real1(loc, name, v, err)
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      real(dp), intent(in) :: v(:)
      integer, intent(inout) :: err
      integer(hid_t) :: sid, aid
      integer(hsize_t) :: dims(1)
      integer :: e
      dims = [size(v, kind=hsize_t)]
      call h5screate_simple_f(1, dims, sid, e)
      call keep(e, err)
      call h5acreate_f(loc, name, H5T_NATIVE_DOUBLE, sid, aid, e)
      call keep(e, err)
      if (e >= 0) then
         call h5awrite_f(aid, H5T_NATIVE_DOUBLE, real(v, c_double), dims, e)
         call keep(e, err)
         call h5aclose_f(aid, e)
      end if
      call h5sclose_f(sid, e)
   end subroutine attr_real1

   subroutine attr_string(loc, name, v, err)
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      character(len=*), intent(in) :: v
      integer, intent(inout) :: err
      integer(hid_t) :: sid, aid, tid
      integer(hsize_t), parameter :: dims(1) = [1]
      integer :: e
      call h5tcopy_f(H5T_FORTRAN_S1, tid, e)
      call keep(e, err)
      call h5tset_size_f(tid, int(max(len(v), 1), size_t), e)
      call keep(e, err)
      call h5screate_f(H5S_SCALAR_F, sid, e)
      call keep(e, err)
      call h5acreate_f(loc, name, tid, sid, aid, e)
      call keep(e, err)
      if (e >= 0) then
         if (len(v) > 0) then
            call h5awrite_f(aid, tid, v, dims, e)
         else
            call h5awrite_f(aid, tid, ' ', dims, e)
         end if
         call keep(e, err)
         call h5aclose_f(aid, e)
      end if
      call h5sclose_f(sid, e)
      call h5tclose_f(tid, e)
   end subroutine attr_string

   pure subroutine keep(e, err)
      integer, intent(in) :: e
      integer, intent(inout) :: err
      if (e < 0) err = e
   end subroutine keep
end module results_hdf5
