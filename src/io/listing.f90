!> Printed listing in the style of Hinton & Owen's OUTPUT routine, and the
!! terminal's header and progress lines.
!!
!! Three levels: NONE (no listing file), SHORT (input summary and the results
!! of the last increment), FULL (echo of the whole input and the results of
!! every increment).  The terminal only gets a summary and one progress line
!! per increment.  Everything printed after the input comes from the records
!! of the run (run information, step record, body and contact fields), the
!! same the result file is written from.
!!
!! Ref: Hinton & Owen (1977), OUTPUT.
module listing
   use kinds, only: dp, i8, pi, stderr
   use errors, only: status_t, STAT_IO
   use strings, only: itoa, rtoa
   use version, only: K2D_VERSION
   use model, only: model_t, ntype_name
   use contact_types, only: contact_def_t, units_name, LAW_ROUGH, UNITS_KGF_UM, UNITS_MODEL, &
         MATCH_SEGMENT, &
                            KGF_PER_NMM2
   use run_plan, only: plan_summary
   use records, only: step_record_t, body_fields_t, contact_fields_t, run_info_t, run_doubts_t, &
         NS_OPEN, &
                      NS_UNLOADING, TS_STICK, TS_PLASTIC, TS_SLIP, MAX_DOUBT_LINES
   use records, only: numbering_report_t
   use renumber, only: RENUMBER_NONE
   implicit none
   private
   public :: list_header, list_method, list_input, list_step, list_displacements, list_stresses, &
             principal_stresses, list_contact, list_progress_header, list_progress
   public :: list_completed, list_failed, list_sliding_warning, list_doubts, list_interfaces
   public :: reversal_warning, list_reversals, doubt_advice
   public :: close_listing, check_listing, SHORT_TABLE_MAX_NODES
   public :: list_numbering
   public :: stress_line, node_line

   !> A SHORT listing lists the whole mesh's tables (displacements of every
   !! node, stresses at every Gauss point) of its last increment up to this
   !! many nodes; beyond, it says that the result file holds them (a
   !! 1e5-dof mesh made a listing of 25 MB, and its formatting cost 0.6 s,
   !! more than the mesh's factorization).  FULL lists them always.
   integer, parameter :: SHORT_TABLE_MAX_NODES = 20000

contains

   !> Close the listing file and check that all of it reached the disk.
   !! gfortran reports no error when a formatted write, a flush or a close
   !! meets a full disk, so the size of the closed file is compared with the
   !! position written (the unit is opened for formatted stream access).  A
   !! shortfall is returned in `status` (when it is still ok).
   subroutine close_listing(u, path, status)
      integer, intent(in) :: u                    !! the listing's unit (stream access)
      character(len=*), intent(in) :: path        !! its file
      type(status_t), intent(inout) :: status
      integer :: pos, ios, ios2, nbytes
      pos = 1
      inquire (unit=u, pos=pos, iostat=ios)
      close (u, iostat=ios2)
      nbytes = -1
      inquire (file=path, size=nbytes)
      if (.not. status%ok()) return
      if (ios /= 0 .or. ios2 /= 0 .or. nbytes < pos - 1) then
         call status%set(STAT_IO, shortfall(path, nbytes, pos - 1))
      end if
   end subroutine close_listing

   !> Has all of the listing written so far reached the disk?  Flushed, then
   !! checked as at its close (close_listing), after every increment that
   !! wrote to it, so that a full disk ends the run at the increment it
   !! stopped the listing; a shortfall is returned in `status`.
   subroutine check_listing(u, path, status)
      integer, intent(in) :: u                    !! the listing's unit (stream access)
      character(len=*), intent(in) :: path        !! its file
      type(status_t), intent(inout) :: status
      integer :: pos, ios, ios2, nbytes
      if (.not. status%ok()) return
      flush (u, iostat=ios2)
      pos = 1
      inquire (unit=u, pos=pos, iostat=ios)
      nbytes = -1
      inquire (file=path, size=nbytes)
      if (ios /= 0 .or. ios2 /= 0 .or. nbytes < pos - 1) then
         call status%set(STAT_IO, shortfall(path, nbytes, pos - 1))
      end if
   end subroutine check_listing

   !> The message of a listing that did not reach the disk whole.
   pure function shortfall(path, nbytes, written) result(msg)
      character(len=*), intent(in) :: path
      integer, intent(in) :: nbytes, written
      character(len=:), allocatable :: msg
      msg = 'cannot write the listing '//path//': '//itoa(max(nbytes, 0))//' of '//itoa(written)// &
            ' bytes reached the disk (is it full?)'
   end function shortfall

   !> Program banner, the control data and the run plan.
   subroutine list_header(u, m, info)
      integer, intent(in) :: u
      type(model_t), intent(in) :: m
      type(run_info_t), intent(in) :: info
      write (u, '(a)') repeat('=', 78)
      write (u, '(a)') ' Kontakt2D '//K2D_VERSION//' - static 2D contact of rough elastic bodies'
      write (u, '(a)') repeat('=', 78)
      write (u, '(a)') ' Title        : '//m%title
      write (u, '(a)') ' Deck         : '//m%deck_file
      write (u, '(a)') ' Analysis     : '//ntype_name(m%ntype)
      write (u, '(a,i0,a,i0,a,i0)') ' Nodes        : ', m%npoin, '   elements: ', m%nelem, &
         '   materials: ', m%nmats
      write (u, '(a,i0,a,i0,a,i0)') ' Equations    : ', info%neq, '   restrained dofs: ', &
            info%nres, &
         '   load cases: ', m%ncase
      write (u, '(a,i0)') ' Increments   : ', m%nincs
      write (u, '(a)') ' Solver       : '//info%solver
      write (u, '(a)') ' Run plan     : '//plan_summary(info%plan)
      call list_interfaces(u, m%contact)
   end subroutine list_header

   !> The contact interfaces: the unit convention of the roughness constants
   !! (KGF_UM unless a UNITS card says otherwise) with the constants as given
   !! and converted to model units, and how the pairs were built.
   !! Ref: SPEC §2.4 (u[mm] = 1e-3 c_n (f p)^m, f = 10.19716 kgf/cm² per N/mm²).
   subroutine list_interfaces(u, c)
      integer, intent(in) :: u
      type(contact_def_t), intent(in) :: c
      integer :: i
      character(len=:), allocatable :: line
      if (.not. allocated(c%ifaces)) return
      do i = 1, size(c%ifaces)
         associate (f => c%ifaces(i))
            if (f%matching == MATCH_SEGMENT .and. f%sides_swapped) write (u, '(a)') &
                  ' Interface '//itoa(i)// &
               ': MATCHING SEGMENT with the sides swapped: the nodes of SURFACE B are projected on &
               &the edges '// &
               'of SURFACE A (the deck''s A is the coarser side)'
            if (f%law /= LAW_ROUGH) cycle
            line = ' Interface '//itoa(i)//': UNITS '//units_name(f%units)
            if (f%units /= UNITS_MODEL) line = line//', model in mm and N/mm2'
            write (u, '(a)') line
            line = '   as given   : CN '//rtoa(f%cn_in)//'  M '//rtoa(f%m_in)//'  CN2 '// &
                  rtoa(f%cn2_in)// &
                   '  M2 '//rtoa(f%m2_in)//'  S '//rtoa(f%s_in)
            if (f%r_given) line = line//'  R '//rtoa(f%r_in)
            write (u, '(a)') line
            if (.not. allocated(f%r_t)) cycle
            if (size(f%r_t) == 0) cycle
            line = '   model units: CN '//rtoa(f%cn)//'  CN2 '//rtoa(f%cn2)//'  R '// &
                  rtoa(minval(f%r_t))
            if (maxval(f%r_t) > minval(f%r_t)) line = line//' .. '//rtoa(maxval(f%r_t))
            line = line//'  (u = CN p^M, length and stress of the model'
            if (f%units == UNITS_KGF_UM) line = line//'; 1 N/mm2 = 10.19716 kgf/cm2'
            write (u, '(a)') line//')'
            if (f%p_reversal_max < huge(1.0_dp)) write (u, '(a)') &
                  '   unloading branch admissible (u_res >= 0, '// &
               'at least as stiff as loading) for reversal pressures up to p* = '// &
               pressure_text(f%p_reversal_max, f%units)// &
               '; beyond, u_res is taken as max(u_res, 0)'
         end associate
      end do
   end subroutine list_interfaces

   !> The method in use: contact scheme, contact system, automatic increments.
   subroutine list_method(u, info)
      integer, intent(in) :: u
      type(run_info_t), intent(in) :: info
      character(len=:), allocatable :: scheme
      if (info%npair == 0) return
      if (.not. info%returning) then
         scheme = 'incremental (the paper: explicit update, repeats on state changes)'
      else if (info%modified) then
         scheme = 'modified Newton (return to the laws, stiffness kept)'
      else
         scheme = 'Newton (return to the laws, tangent every solution)'
      end if
      write (u, '(a)') ' Contact      : '//itoa(info%npair)//' pairs, '//scheme
      if (len(info%system) > 0) write (u, '(a)') ' '//info%system
      if (info%autoinc) write (u, &
                               '(a)') ' Increments   : automatic (cut on failure or chatter, &
                               &smallest step '// &
         rtoa(info%autoinc_min)//' of a deck increment)'
   end subroutine list_method

   !> What the equation numbering did (the automatic choice of the solver,
   !! the renumbering and the profile before and after): two to four lines
   !! for the listing header and the terminal.
   subroutine list_numbering(u, rep)
      integer, intent(in) :: u
      type(numbering_report_t), intent(in) :: rep
      if (allocated(rep%solver_choice)) then
         if (len(rep%solver_choice) > 0) write (u, '(a)') ' Solver choice: '//rep%solver_choice
      end if
      write (u, '(a)') ' Renumbering  : '//rep%method//' ('//rep%reason//')'
      write (u, '(a)') ' Profile      : user order '// &
         profile_text(rep%profile_before, rep%mean_before, rep%max_before)
      if (rep%method /= RENUMBER_NONE) then
         write (u, '(a)') '                '//rep%method//'        '// &
            profile_text(rep%profile_after, rep%mean_after, rep%max_after)
      end if
   end subroutine list_numbering

   !> "skyline N, mean column height H, max M".
   function profile_text(n, mean, mx) result(s)
      integer(i8), intent(in) :: n
      real(dp), intent(in) :: mean
      integer, intent(in) :: mx
      character(len=:), allocatable :: s
      character(len=24) :: b
      write (b, '(i0)') n
      s = 'skyline '//trim(b)//', mean column height '//rtoa(mean, '(f0.1)')//', max '//itoa(mx)
   end function profile_text

   !> Echo of the input data (FULL listing).
   subroutine list_input(u, m)
      integer, intent(in) :: u
      type(model_t), intent(in) :: m
      integer :: ip, ie, k, i
      write (u, '(/a)') ' NODAL COORDINATES'
      write (u, '(a)') '   NODE         X-COORD         Y-COORD'
      do ip = 1, m%npoin
         write (u, '(i7, 2es16.7)') ip, m%coord(:, ip)
      end do
      write (u, '(/a)') ' ELEMENT CONNECTIVITY'
      write (u, '(a)') '   ELEM  MAT  NODES'
      do ie = 1, m%nelem
         write (u, '(i7, i5, 9i7)') ie, m%matno(ie), m%lnods(1:m%nnode_e(ie), ie)
      end do
      write (u, '(/a)') ' MATERIALS'
      write (u, '(a)') '    MAT               E              NU           THICK'
      do k = 1, m%nmats
         write (u, '(i7, 3es16.7)') k, m%mats(k)%young, m%mats(k)%poiss, m%mats(k)%thick
      end do
      write (u, '(/a)') ' RESTRAINTS'
      write (u, '(a)') '   NODE  CODE   PRESCRIBED-U    PRESCRIBED-V  CASE'
      do k = 1, size(m%fixes)
         write (u, '(i7, 3x, 2i1, 2es16.7, i6)') m%fixes(k)%node, merge(1, 0, m%fixes(k)%fixed), &
            m%fixes(k)%value, m%fixes(k)%icase
      end do
      if (size(m%point_loads) > 0) then
         write (u, '(/a)') ' POINT LOADS'
         write (u, '(a)') '   NODE              FX              FY  CASE'
         do k = 1, size(m%point_loads)
            write (u, '(i7, 2es16.7, i6)') m%point_loads(k)%node, m%point_loads(k)%force, &
                  m%point_loads(k)%icase
         end do
      end if
      if (size(m%edge_loads) > 0) then
         write (u, '(/a)') ' EDGE LOADS (nodes in element order: start, end, mid)'
         do k = 1, size(m%edge_loads)
            associate (e => m%edge_loads(k))
               ! e%nn (2 or 3) node fields: a fixed count would read the text after them as one
               write (u, '(a,i0,a,'//itoa(e%nn)//'i7,a,i0)') '   element ', e%ielem, '  nodes', &
                     e%nodes(1:e%nn), &
                  '  case ', e%icase
               write (u, '(a,3es14.5)') '      pressure  ', e%pn(1:e%nn)
               write (u, '(a,3es14.5)') '      tangential', e%pt(1:e%nn)
            end associate
         end do
      end if
      if (size(m%body_loads) > 0) then
         write (u, '(/a)') ' BODY FORCES'
         do k = 1, size(m%body_loads)
            write (u, '(a,i0,a,2es14.5,a,i0)') '   material ', m%body_loads(k)%imat, '  b =', &
               m%body_loads(k)%b, '  case ', m%body_loads(k)%icase
         end do
      end if
      write (u, '(/a)') ' LOAD HISTORY (total factor of each load case after each increment)'
      do i = 1, m%nincs
         write (u, '(i7, *(f12.5))') i, m%lambda(:, i)
      end do
   end subroutine list_input

   !> The results of one step: displacements and reactions, the contact
   !! table (contact models), the Gauss-point stresses.
   subroutine list_step(u, m, step, body, contact, path, status, short)
      integer, intent(in) :: u
      type(model_t), intent(in) :: m
      type(step_record_t), intent(in) :: step
      type(body_fields_t), intent(in) :: body
      type(contact_fields_t), intent(in), optional :: contact   !! listed when step%contact
      character(len=*), intent(in), optional :: path            !! the listing's file:
                                                                !! with `status`, the
      type(status_t), intent(inout), optional :: status         !! listing is then checked
                                                                !! (check_listing)
      logical, intent(in), optional :: short                    !! a SHORT listing (see
                                                                !! SHORT_TABLE_MAX_NODES)
      logical :: tables
      tables = .true.
      if (present(short)) tables = .not. short .or. m%npoin <= SHORT_TABLE_MAX_NODES
      call list_displacements(u, m, step, body, tables)
      if (step%contact .and. present(contact)) call list_contact(u, m%contact, step, contact)
      if (tables) then
         call list_stresses(u, m, body%gp_start, body%xygp, body%sig_gp)
      else
         write (u, '(/a)') ' STRESSES AT GAUSS POINTS: '//itoa(size(body%sig_gp, 2))// &
               ' points, in the result file'// &
            short_tables_note()
      end if
      if (present(path) .and. present(status)) call check_listing(u, path, status)
   end subroutine list_step

   !> Why a SHORT listing leaves a table out, and how to get it.
   function short_tables_note() result(s)
      character(len=:), allocatable :: s
      s = ' (the SHORT listing lists the mesh''s tables up to '//itoa(SHORT_TABLE_MAX_NODES)// &
            ' nodes;'// &
          ' OPTIONS LISTING FULL lists them)'
   end function short_tables_note

   !> Displacements (unless table = .false.: a line saying where they are)
   !! and reactions of one step.
   subroutine list_displacements(u, m, step, body, table)
      integer, intent(in) :: u
      type(model_t), intent(in) :: m
      type(step_record_t), intent(in) :: step
      type(body_fields_t), intent(in) :: body
      logical, intent(in), optional :: table
      integer :: ip
      logical :: whole, ok
      character(len=39) :: line
      whole = .true.
      if (present(table)) whole = table
      write (u, '(/a)') repeat('-', 78)
      write (u, '(a,i0,a,*(f11.5))') ' INCREMENT ', step%step, '   load factor(s):', step%lambda
      if (allocated(step%doubts)) then
         if (len(step%doubts) > 0) write (u, '(a)') ' DOUBTFUL: '//step%doubts
      end if
      write (u, '(a)') repeat('-', 78)
      if (.not. whole) then
         write (u, '(/a)') ' DISPLACEMENTS: '//itoa(m%npoin)//' nodes, in the result file'// &
               short_tables_note()
         write (u, '(a, 2es16.7)') '   largest |u_x|, |u_y|', maxval(abs(body%disp(1, :))), &
               maxval(abs(body%disp(2, :)))
      else
         write (u, '(/a)') ' DISPLACEMENTS'
         write (u, '(a)') '   NODE          X-DISP          Y-DISP'
         do ip = 1, m%npoin
            call node_line(ip, body%disp(:, ip), line, ok)
            if (ok) then
               write (u, '(a)') line
            else
               write (u, '(i7, 2es16.7)') ip, body%disp(:, ip)
            end if
         end do
      end if
      write (u, '(/a)') ' REACTIONS'
      write (u, '(a)') '   NODE         X-FORCE         Y-FORCE'
      do ip = 1, m%npoin
         if (any(body%restrained(:, ip))) write (u, '(i7, 2es16.7)') ip, body%react(:, ip)
      end do
      write (u, '(a, 2es16.7)') '  TOTAL', sum(body%react(1, :)), sum(body%react(2, :))
   end subroutine list_displacements

   !> Gauss-point stresses with principal values (STRESS of Hinton & Owen).
   subroutine list_stresses(u, m, gp_start, xygp, sig)
      integer, intent(in) :: u
      type(model_t), intent(in) :: m
      integer, intent(in) :: gp_start(:)       !! (nelem+1) first Gauss point of each element
      real(dp), intent(in) :: xygp(:, :)       !! (2, ngp)
      real(dp), intent(in) :: sig(:, :)        !! (4, ngp)
      integer :: ie, ig
      real(dp) :: s1, s2, ang, v(8)
      character(len=115) :: line
      logical :: ok
      write (u, '(/a)') ' STRESSES AT GAUSS POINTS'
      write (u, '(a)') '   ELEM  G.P.     X-COORD     Y-COORD   XX-STRESS   YY-STRESS   &
      &XY-STRESS'// &
         '   ZZ-STRESS   MAX P.S.   MIN P.S.  ANGLE'
      do ie = 1, m%nelem
         do ig = gp_start(ie), gp_start(ie + 1) - 1
            call principal_stresses(sig(:, ig), s1, s2, ang)
            ! the line built without the run time's conversion where certain (stress_line)
            v(1:2) = xygp(:, ig)
            v(3:6) = sig(:, ig)
            v(7:8) = [s1, s2]
            call stress_line(ie, ig - gp_start(ie) + 1, v, ang, line, ok)
            if (ok) then
               write (u, '(a)') line
            else
               write (u, '(i7, i5, 8es12.4, f7.2)') ie, ig - gp_start(ie) + 1, xygp(:, ig), &
                     sig(:, ig), s1, s2, ang
            end if
         end do
      end do
   end subroutine list_stresses

   !> Contact table of one step: one line per pair.  The stresses of pairs of
   !! zero area are listed as zero (the result file extrapolates them).
   subroutine list_contact(u, c, step, cf)
      integer, intent(in) :: u
      type(contact_def_t), intent(in) :: c
      type(step_record_t), intent(in) :: step
      type(contact_fields_t), intent(in) :: cf
      integer :: j
      character(len=5) :: ns, ts
      real(dp) :: pn, pt
      write (u, '(/a)') ' CONTACT PAIRS'
      write (u, '(a,i0,a,i0,a,es10.3,a,es10.3,a,es10.3)') '   solutions: ', step%solutions, &
            '   repeats: ', &
         step%repeats, '   out-of-balance: ', step%residual, '   normal-law drift: ', step%drift, &
         '   tangential-law drift: ', step%drift_t
      write (u, '(a)') '   PAIR  NODE-A  NODE-B     X-COORD     Y-COORD        AREA    PRESSURE    &
      &   SHEAR'// &
         '     CLOSURE        SLIP  SLIP-IRREV    MU  NORM  TANG'
      do j = 1, size(c%pairs)
         associate (p => c%pairs(j))
            select case (cf%normal_state(j))
            case (NS_OPEN)
               ns = 'open'
            case (NS_UNLOADING)
               ns = 'unld'
            case default
               ns = 'load'
            end select
            select case (cf%tangential_state(j))
            case (TS_STICK)
               ts = 'stick'
            case (TS_PLASTIC)
               ts = 'plast'
            case (TS_SLIP)
               ts = 'slip'
            end select
            if (cf%normal_state(j) == NS_OPEN) ts = '-'
            pn = 0.0_dp
            pt = 0.0_dp
            if (p%area > 0.0_dp) then
               pn = cf%pressure(j)
               pt = cf%shear(j)
            end if
            write (u, '(i7, 2i8, 8es12.4, f6.3, 2(1x,a5))') j, p%node_a, p%node_b, p%position, &
                  p%area, pn, pt, &
               cf%closure(j), cf%slip(j), cf%slip_irreversible(j), cf%friction(j), ns, ts
         end associate
      end do
      write (u, '(a,es14.6,a,es14.6)') '   sum of normal forces:', sum(cf%force_normal), &
            '   of tangential forces:', &
         sum(cf%force_tangential)
      ! the energy dissipated by the contact laws (module contact_energy), per interface
      if (allocated(cf%dissipated_energy)) then
         do j = 1, size(cf%dissipated_energy)
            write (u, '(a,i0,a,es14.6,a,es14.6)') '   energy dissipated, interface ', j, &
                  ': cumulative', &
               cf%dissipated_energy(j), '   in this increment', cf%dissipated_increment(j)
         end do
      end if
   end subroutine list_contact

   !> Column titles of the terminal's progress lines.
   subroutine list_progress_header(u, contact)
      integer, intent(in) :: u
      logical, intent(in) :: contact          !! a contact model
      if (contact) then
         write (u, '(a)') '   inc  load factor     max |u|  closed  slip  solves rep   residual    &
         &time [s]'
      else
         write (u, '(a)') '   inc  load factor     max |u|        sum Rx        sum Ry    time [s]'
      end if
   end subroutine list_progress_header

   !> One progress line for the terminal.  Its load factor is the factor of
   !! load case icase (run_summary's stage_case: the case whose factor varies
   !! most, which the summary's stages follow), with its sign (a case taken
   !! below zero, a pull, shows as such).
   subroutine list_progress(u, step, body, seconds, icase, contact)
      integer, intent(in) :: u
      type(step_record_t), intent(in) :: step
      type(body_fields_t), intent(in) :: body
      real(dp), intent(in) :: seconds                           !! elapsed since the
                                                                !! start of the run
      integer, intent(in) :: icase                              !! the load case shown
      type(contact_fields_t), intent(in), optional :: contact   !! used when step%contact
      integer :: ic
      ic = min(max(icase, 1), size(step%lambda))
      if (step%contact .and. present(contact) .and. .not. step%full) then
         ! a step whose body fields were skipped (neither written nor listed: step_record_t%full):
         ! its contact figures, a dash for max |u|, which is not known for it
         write (u, '(i6, f13.5, a12, i8, i6, i8, i4, es11.3, f12.3)') step%step, &
               step%lambda(ic), &
            '-', count(contact%normal_state /= NS_OPEN), &
            count(contact%normal_state /= NS_OPEN .and. contact%tangential_state == TS_SLIP), &
            step%solutions, &
            step%repeats, step%residual, seconds
      else if (step%contact .and. present(contact)) then
         write (u, '(i6, f13.5, es12.4, i8, i6, i8, i4, es11.3, f12.3)') step%step, &
               step%lambda(ic), &
            maxval(sqrt(body%disp(1, :)**2 + body%disp(2, :)**2)), &
            count(contact%normal_state /= NS_OPEN), &
            count(contact%normal_state /= NS_OPEN .and. contact%tangential_state == TS_SLIP), &
            step%solutions, &
            step%repeats, step%residual, seconds
      else
         write (u, '(i6, f13.5, 3es14.5, f12.3)') step%step, &
               step%lambda(ic), &
            maxval(sqrt(body%disp(1, :)**2 + body%disp(2, :)**2)), sum(body%react(1, :)), &
            sum(body%react(2, :)), seconds
      end if
   end subroutine list_progress

   !> The terminal's last lines of a completed run.
   subroutine list_completed(u, completed, results_path)
      integer, intent(in) :: u
      integer, intent(in) :: completed               !! steps finished
      character(len=*), intent(in) :: results_path
      write (u, '(a)') repeat('-', 78)
      write (u, '(a)') ' Completed '//itoa(completed)//' increment(s); results in '//results_path
   end subroutine list_completed

   !> Where a failed run stopped and what its result file keeps (error unit,
   !! or the listing).
   subroutine list_failed(u, completed, message, results_path, results_every)
      integer, intent(in) :: u
      integer, intent(in) :: completed               !! steps finished before the
                                                     !! failure (-1: at set-up)
      character(len=*), intent(in) :: message        !! why
      character(len=*), intent(in) :: results_path
      integer, intent(in) :: results_every           !! OPTIONS RESULTS
      if (completed < 0) then
         write (u, '(a)') 'kontakt2d: the set-up failed before the first increment: '//message
         write (u, '(a)') 'kontakt2d: '//results_path// &
               ' keeps the mesh and this status (no increment)'
         return
      end if
      write (u, '(a)') 'kontakt2d: increment '//itoa(completed + 1)//' failed: '//message
      if (results_every > 1) then
         write (u, '(a)') 'kontakt2d: '//itoa(completed)//' increment(s) completed; '// &
            results_path//' keeps one in '//itoa(results_every)//' (OPTIONS RESULTS), the last '// &
            'of them increment '//itoa((completed/results_every)*results_every)
      else
         write (u, '(a)') 'kontakt2d: '//itoa(completed)// &
               ' completed increment(s) are kept in '//results_path
      end if
   end subroutine list_failed

   !> Warning: a pair slid more than 10 % of the pair spacing.
   subroutine list_sliding_warning(u, step, pair, slip, spacing)
      integer, intent(in) :: u, step, pair
      real(dp), intent(in) :: slip, spacing          !! |u_T| of the pair, distance
                                                     !! to the nearest pair
      write (u, '(a)') 'kontakt2d: warning: increment '//itoa(step)//': pair '//itoa(pair)// &
         ' has slid '//rtoa(slip)//', more than 10 % of the pair spacing ('// &
         rtoa(spacing)//'): node-to-node contact assumes small sliding (the partners '// &
         'must stay opposite each other); refine the contact mesh or use stiffer roughness data'
   end subroutine list_sliding_warning

   !> The end of a run that completed with doubts (exit code 4): the summary
   !! and where the results are (the terminal, which had a warning at every
   !! doubtful increment), or the summary and the doubtful increments with the
   !! pairs concerned (the listing: results_path = '').
   subroutine list_doubts(u, doubts, summary, results_path, info)
      integer, intent(in) :: u
      type(run_doubts_t), intent(in) :: doubts
      character(len=*), intent(in) :: summary        !! one line: how many of each kind
      character(len=*), intent(in) :: results_path   !! '' in the listing
      type(run_info_t), intent(in), optional :: info !! the scheme and options of
                                                     !! the run (for the advice;
                                                     !! without it none)
      integer :: k, k0
      write (u, '(a)') repeat('-', 78)
      write (u, '(a)') 'kontakt2d: completed with doubts: '//summary
      if (len(results_path) > 0) then
         write (u, '(a)') 'kontakt2d: results (status "doubtful") in '//results_path// &
               '; the increments and '// &
            'pairs concerned are named above and in the listing'
         return
      end if
      k0 = 1
      do k = 1, len(doubts%details) + 1
         if (k <= len(doubts%details)) then
            if (doubts%details(k:k) /= new_line('a')) cycle
         end if
         write (u, '(a)') '  '//doubts%details(k0:k - 1)
         k0 = k + 1
      end do
      if (doubts%steps > MAX_DOUBT_LINES) write (u, '(a)') '  ... and '// &
            itoa(doubts%steps - MAX_DOUBT_LINES)// &
         ' more doubtful increment(s)'
      if (present(info)) then
         write (u, '(a)') '  (frozen states, law drift and invariant violations: &
         &docs/accuracy-and-stability.md; '// &
            doubt_advice(info)//')'
      else
         write (u, '(a)') '  (frozen states, law drift and invariant violations: &
         &docs/accuracy-and-stability.md)'
      end if
   end subroutine list_doubts

   !> What may remove the doubts of a run, for the scheme and the options it
   !! used: SCHEME NEWTON only to a run of the incremental scheme (Newton holds
   !! the laws and the balance at every increment end), OPTIONS AUTOINC only to
   !! a run without it (a run with it: a smaller smallest step MINFRAC), and
   !! smaller increments to every run.
   pure function doubt_advice(info) result(text)
      type(run_info_t), intent(in) :: info
      character(len=:), allocatable :: text
      text = 'what may remove them: smaller increments'
      if (info%autoinc) then
         text = text//', or a smaller AUTOINC MINFRAC (now '//rtoa(info%autoinc_min)//')'
      else
         text = text//', OPTIONS AUTOINC'
      end if
      if (.not. info%returning) then
         text = text//', SCHEME NEWTON (the laws and the balance held at every increment end)'
      end if
   end function doubt_advice

   !> Warning for the pairs that took their reversal point A in a step beyond
   !! the admissible range of their unloading law, p_A > p* (contact_laws'
   !! admissible_reversals; docs/contact.md): how many, and the pair farthest
   !! beyond (largest p_A / p*) with p_A, p* and what the law does there: a
   !! negative residual closure u_A - c_n2 p_A^m2 (u_A = c_n p_A^m) is taken as
   !! 0, a branch softer than loading at A is followed as given.  '' if none.
   pure function reversal_warning(c, step, pa_old, pa) result(text)
      type(contact_def_t), intent(in) :: c
      integer, intent(in) :: step                   !! the step (increment of the result file)
      real(dp), intent(in) :: pa_old(:)             !! (npair) reversal pressures
                                                    !! before the step (0: none)
      real(dp), intent(in) :: pa(:)                 !! (npair) after it
      character(len=:), allocatable :: text
      integer :: j, n, jw
      real(dp) :: r, rw, ures
      text = ''
      n = 0
      jw = 0
      rw = 0.0_dp
      if (.not. allocated(c%pairs) .or. .not. allocated(c%ifaces)) return
      do j = 1, min(size(pa_old), size(pa), size(c%pairs))
         if (.not. (pa(j) > pa_old(j))) cycle
         associate (f => c%ifaces(c%pairs(j)%iface))
            if (f%law /= LAW_ROUGH .or. .not. (pa(j) > f%p_reversal_max)) cycle
            n = n + 1
            r = pa(j)/f%p_reversal_max
            if (r > rw) then
               rw = r
               jw = j
            end if
         end associate
      end do
      if (n == 0) return
      associate (f => c%ifaces(c%pairs(jw)%iface), pr => c%pairs(jw))
         text = 'increment '//itoa(step)//': '//itoa(n)// &
               ' pair(s) unload from beyond the admissible range of '// &
                'their unloading law; the farthest: pair '//itoa(jw)//' (nodes '// &
                itoa(pr%node_a)//'-'// &
                itoa(pr%node_b)//', interface '//itoa(pr%iface)//') from p_A = '// &
                pressure_text(pa(jw), f%units)// &
                ' > p* = '//pressure_text(f%p_reversal_max, f%units)
         ures = f%cn*pa(jw)**f%m - f%cn2*pa(jw)**f%m2
         if (ures < 0.0_dp) then
            text = text//': its residual closure u_A - c_n2 p_A^m2 = '//rtoa(ures)// &
                   trim(merge(' (model units)', ' mm           ', f%units == UNITS_MODEL))// &
                   ' < 0 is taken as 0 '// &
                   '(unloading along u = u_A (p/p_A)^m2; docs/contact.md)'
         else
            text = text//': its unloading branch is softer than loading at A, followed as given &
            &(docs/contact.md)'
         end if
      end associate
   end function reversal_warning

   !> The pairs of a step that took a reversal point beyond the admissible
   !! range of their unloading law (reversal_warning): the warning on the
   !! terminal (the error unit, as every warning) and in the listing, and in
   !! the step record (the increment's attribute `warnings` of the result
   !! file); counted in nwarn.
   subroutine list_reversals(c, pa_old, pa, step, lu, have_lis, nwarn)
      type(contact_def_t), intent(in) :: c
      real(dp), intent(in) :: pa_old(:), pa(:)      !! (npair) reversal pressures
                                                    !! before and after the step
      type(step_record_t), intent(inout) :: step    !! the step (its number; warnings set)
      integer, intent(in) :: lu                     !! listing unit
      logical, intent(in) :: have_lis               !! a listing is written
      integer, intent(inout) :: nwarn               !! warnings of the run
      step%warnings = reversal_warning(c, step%step, pa_old, pa)
      if (len(step%warnings) == 0) return
      write (stderr, '(a)') 'kontakt2d: warning: '//step%warnings
      if (have_lis) write (lu, '(a)') ' WARNING: '//step%warnings
      nwarn = nwarn + 1
   end subroutine list_reversals

   !> A pressure of the model with its unit, and in kgf/cm2 for UNITS KGF_UM.
   pure function pressure_text(p, units) result(text)
      real(dp), intent(in) :: p                     !! pressure in model units
      integer, intent(in) :: units                  !! UNITS of the interface
      character(len=:), allocatable :: text
      if (units == UNITS_MODEL) then
         text = rtoa(p)//' (model units)'
      else
         text = rtoa(p)//' N/mm2'
         if (units == UNITS_KGF_UM) text = text//' ('//rtoa(p*KGF_PER_NMM2)//' kgf/cm2)'
      end if
   end function pressure_text

   !> In-plane principal stresses and the angle (degrees) of the first from x.
   pure subroutine principal_stresses(sig, s1, s2, angle)
      real(dp), intent(in) :: sig(4)
      real(dp), intent(out) :: s1, s2, angle
      real(dp) :: c, r
      c = 0.5_dp*(sig(1) + sig(2))
      r = sqrt((0.5_dp*(sig(1) - sig(2)))**2 + sig(3)**2)
      s1 = c + r
      s2 = c - r
      if (r > 0.0_dp) then
         angle = 0.5_dp*atan2(2.0_dp*sig(3), sig(1) - sig(2))*180.0_dp/pi
      else
         angle = 0.0_dp
      end if
   end subroutine principal_stresses

   !> One line of the Gauss-point table, as '(i7, i5, 8es12.4, f7.2)' writes it
   !! (see put_es); ok = .false. when a field is left to the run time.
   pure subroutine stress_line(ie, ig, v, ang, line, ok)
      integer, intent(in) :: ie, ig
      real(dp), intent(in) :: v(8)             !! x, y, the 4 stresses, the 2 principal ones
      real(dp), intent(in) :: ang
      character(len=115), intent(out) :: line
      logical, intent(out) :: ok
      integer :: k
      call put_int(ie, 7, line(1:7), ok)
      if (ok) call put_int(ig, 5, line(8:12), ok)
      do k = 1, 8
         if (ok) call put_es(v(k), 12, 4, line(1 + 12*k:12 + 12*k), ok)
      end do
      if (ok) call put_f2(ang, line(109:115), ok)
   end subroutine stress_line

   !> A node's line of the displacement or reaction table, as '(i7, 2es16.7)'.
   pure subroutine node_line(ip, v, line, ok)
      integer, intent(in) :: ip
      real(dp), intent(in) :: v(2)
      character(len=39), intent(out) :: line
      logical, intent(out) :: ok
      call put_int(ip, 7, line(1:7), ok)
      if (ok) call put_es(v(1), 16, 7, line(8:23), ok)
      if (ok) call put_es(v(2), 16, 7, line(24:39), ok)
   end subroutine node_line

   !> A non-negative integer right-justified in its field (Iw).
   pure subroutine put_int(n, w, field, ok)
      integer, intent(in) :: n, w
      character(len=w), intent(out) :: field
      logical, intent(out) :: ok
      integer :: k, q
      field = ' '
      ok = n >= 0 .and. n < 10**min(9, w)
      if (.not. ok) return
      q = n
      do k = w, 1, -1
         field(k:k) = achar(48 + mod(q, 10))
         q = q/10
         if (q == 0) exit
      end do
   end subroutine put_int

   !> x as ESw.d prints it (w the length of field; d <= 8 digits after the point,
   !! a two-digit exponent), right-justified, without the run time's conversion (its
   !! snprintf made most of the cost of a long listing).  The d + 1
   !! significant digits are m = |x| 10^(d-e) rounded to the nearest integer;
   !! m is computed with a relative error of a few rounding units, under 1e-7
   !! in absolute terms for d <= 8, so rounding it gives the correctly rounded
   !! digits the run time prints unless m lies within TIE_MARGIN of a half.
   !! ok = .false. (the caller writes the value with the run time) for such
   !! near-ties, for zero, subnormal and non-finite x and for exponents
   !! beyond two digits.
   pure subroutine put_es(x, w, d, field, ok)
      real(dp), intent(in) :: x
      integer, intent(in) :: w, d
      character(len=w), intent(out) :: field
      logical, intent(out) :: ok
      real(dp), parameter :: TIE_MARGIN = 1.0e-4_dp
      real(dp) :: ax, m, top
      integer :: e, im, k, q
      field = ' '
      ax = abs(x)
      ok = .false.
      if (.not. (ax >= tiny(ax) .and. ax <= huge(ax))) return
      if (d < 1 .or. d > 8 .or. w < d + 7) return
      top = 10.0_dp**(d + 1)
      e = floor(log10(ax))
      if (abs(e) > 98) return
      m = ax*10.0_dp**(d - e)
      if (m >= top) then
         e = e + 1
         m = ax*10.0_dp**(d - e)
      else if (m < top/10) then
         e = e - 1
         m = ax*10.0_dp**(d - e)
      end if
      if (abs(m - aint(m) - 0.5_dp) < TIE_MARGIN) return
      im = nint(m)
      if (im >= nint(top)) then
         im = im/10
         e = e + 1
      end if
      if (im < nint(top/10) .or. abs(e) > 99) return
      ! d.ddddE+ee
      field(w - 3:w - 2) = 'E+'
      if (e < 0) field(w - 2:w - 2) = '-'
      field(w - 1:w - 1) = achar(48 + abs(e)/10)
      field(w:w) = achar(48 + mod(abs(e), 10))
      q = im
      do k = w - 4, w - 3 - d, -1
         field(k:k) = achar(48 + mod(q, 10))
         q = q/10
      end do
      field(w - 4 - d:w - 4 - d) = '.'
      field(w - 5 - d:w - 5 - d) = achar(48 + q)
      if (x < 0.0_dp) field(w - 6 - d:w - 6 - d) = '-'
      ok = .true.
   end subroutine put_es

   !> x as F7.2 prints it (the angle of the stress table), right-justified;
   !! ok = .false. for values that round to zero, need more than 7
   !! characters or lie within TIE_MARGIN of a rounding tie (see put_es).
   pure subroutine put_f2(x, field, ok)
      real(dp), intent(in) :: x
      character(len=7), intent(out) :: field
      logical, intent(out) :: ok
      real(dp), parameter :: TIE_MARGIN = 1.0e-4_dp
      real(dp) :: m
      integer :: im, k, q
      field = ' '
      ok = .false.
      if (.not. abs(x) < 999.0_dp) return
      m = abs(x)*100.0_dp
      if (abs(m - aint(m) - 0.5_dp) < TIE_MARGIN) return
      im = nint(m)
      if (im == 0) return
      field(6:7) = achar(48 + mod(im/10, 10))//achar(48 + mod(im, 10))
      field(5:5) = '.'
      q = im/100
      k = 4
      do
         field(k:k) = achar(48 + mod(q, 10))
         q = q/10
         k = k - 1
         if (q == 0) exit
      end do
      if (x < 0.0_dp) field(k:k) = '-'
      ok = .true.
   end subroutine put_f2
end module listing
