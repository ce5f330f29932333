!> Data of the contact definition: interfaces (the interface law and its
!! parameters, in model units), contact pairs, and the algorithm options.
!! Plain data filled by contact_definition from the deck's contact
!! specification (model/contact_spec, which holds the same interface type
!! with the constants as given); the laws themselves live in src/contact/.
!!
!! Model units: the conversion of the literature constants (µm and kgf/cm²)
!! is done once, when the model is defined after reading (SPEC §2.4), so that here
!!     u_n = cn * p^m         (loading, virgin curve)
!!     k_T^e = p^S / r_t      (elastic tangential stiffness per unit area)
!! hold with u in the model's length unit and p in its stress unit.
module contact_types
   use kinds, only: dp
   implicit none
   private

   public :: interface_t, contact_pair_t, contact_options_t, contact_def_t, rigid_body_t
   public :: LAW_ROUGH, LAW_IDEAL, FRICTION_NONE, FRICTION_COULOMB, FRICTION_FREDRIKSSON, &
             UNITS_KGF_UM, UNITS_N_UM, UNITS_MODEL, UPDATE_EXPLICIT, UPDATE_RETURN, &
             SLIP_IRREVERSIBLE, SLIP_GROSS, NEWCLOSED_SECANT, NEWCLOSED_TANGENT, KGF_PER_NMM2, &
             units_name, friction_name, update_name, slip_name
   public :: PAIR_NODE, PAIR_SEGMENT, PAIR_RIGID, MATCH_NODE, MATCH_SEGMENT, MAX_PAIR_NODES, &
             RIGID_POLYLINE, RIGID_CIRCLE, law_name, matching_name, rigid_shape_name

   integer, parameter :: LAW_ROUGH = 1             !! the paper's rough interface (springs)
   integer, parameter :: LAW_IDEAL = 2             !! smooth contact with Coulomb
                                                   !! friction (reference)

   integer, parameter :: FRICTION_NONE = 0         !! no tangential stiffness, no friction
   integer, parameter :: FRICTION_COULOMB = 1      !! constant mu
   integer, parameter :: FRICTION_FREDRIKSSON = 2  !! slip-hardening mu(v_e), SPEC D1

   integer, parameter :: UNITS_KGF_UM = 1          !! cn in µm/(kgf/cm²)^m, R in the same system
   integer, parameter :: UNITS_N_UM = 2            !! cn in µm/(N/mm²)^m
   integer, parameter :: UNITS_MODEL = 3           !! constants already in model units

   integer, parameter :: UPDATE_EXPLICIT = 1       !! the paper: F += K dU with K
                                                   !! from the previous increment
   integer, parameter :: UPDATE_RETURN = 2         !! return to the curves, repeat
                                                   !! until in equilibrium

   integer, parameter :: SLIP_IRREVERSIBLE = 1     !! v_e from all irreversible slip (SPEC §2.3 a)
   integer, parameter :: SLIP_GROSS = 2            !! v_e from gross slip only (SPEC §2.3 b)

   integer, parameter :: NEWCLOSED_SECANT = 1      !! a newly closed pair: secant
                                                   !! of its penetration (SPEC §4.3)
   integer, parameter :: NEWCLOSED_TANGENT = 2     !! ... or the virgin tangent
                                                   !! at the floor pressure

   ! What the master side (B) of a pair is: a node (the paper's node-to-node
   ! spring), a point on an edge of body B (node-to-segment), or a point of a
   ! rigid body's profile, which moves with the body's reference node.
   integer, parameter :: PAIR_NODE = 0             !! node a - node b
   integer, parameter :: PAIR_SEGMENT = 1          !! node a - point of an edge of B (2 or 3 nodes)
   integer, parameter :: PAIR_RIGID = 2            !! node a - point of a rigid
                                                   !! profile (reference node)
   integer, parameter :: MAX_PAIR_NODES = 8        !! slave node + up to 7 master nodes

   integer, parameter :: MATCH_NODE = 1            !! node-to-node pairing (the paper's default)
   integer, parameter :: MATCH_SEGMENT = 2         !! node-to-segment pairing (non-matching meshes)

   integer, parameter :: RIGID_POLYLINE = 1        !! straight segments (FLAT
                                                   !! is a two-point polyline)
   integer, parameter :: RIGID_CIRCLE = 2          !! circle (a sphere in axisymmetry)

   !> kgf/cm² per N/mm² (1 kgf/cm² = 0.0980665 N/mm²).
   real(dp), parameter :: KGF_PER_NMM2 = 1.0_dp/0.0980665_dp

   !> One contact interface: the law of the rough layer between two surfaces.
   type :: interface_t
      integer :: law = LAW_ROUGH
      integer :: units = UNITS_KGF_UM
      ! as given in the deck (input units), for the listing and the result file
      real(dp) :: cn_in = 0.0_dp, m_in = 0.0_dp, cn2_in = 0.0_dp, m2_in = 0.0_dp
      real(dp) :: r_in = 0.0_dp, s_in = 0.0_dp
      logical :: r_given = .false.     !! R given; otherwise 2 cn m (1 + nu), eq. (2.8)
      logical :: s_given = .false.     !! S given; otherwise 1 - m (SPEC D3)
      ! in model units
      real(dp) :: cn = 0.0_dp          !! loading: u = cn p^m
      real(dp) :: m = 0.0_dp
      real(dp) :: cn2 = 0.0_dp         !! unloading: u = u_A - cn2 (p_A^m2 - p^m2)
      real(dp) :: m2 = 0.0_dp
      real(dp) :: p_reversal_max = huge(1.0_dp) !! largest reversal pressure of
                                                !! an admissible unloading branch
                                                !! (contact_laws' admissible_reversals, set by
                                                !! contact_definition)
      real(dp) :: s = 0.0_dp           !! k_T^e = p^S / r_t
      real(dp), allocatable :: r_t(:)  !! per pair of this interface (R depends on nu when computed)
      ! tangential law and friction
      integer :: friction = FRICTION_COULOMB
      real(dp) :: mu_m = 0.0_dp        !! Coulomb mu, or Fredriksson's macroscopic mu_m
      real(dp) :: beta = 1.0_dp        !! Fredriksson: initial coefficient beta mu_m
      real(dp) :: n_hard = 0.0_dp      !! Fredriksson: hardening rate n [1/length]
      logical :: hardening = .true.    !! bilinear branch between 0.625 mu p_n and mu p_n
      real(dp) :: kappa = 0.045_dp     !! k_T^p / k_T^e, eq. (2.6)/(4.17)
      integer :: slip_def = SLIP_IRREVERSIBLE
      ! pairing
      real(dp) :: tol = -1.0_dp        !! pairing tolerance (< 0: default from the mesh size)
      integer :: matching = MATCH_NODE !! node-to-node or node-to-segment (surface B only)
      logical :: sides_swapped = .false. !! MATCHING SEGMENT built from B's
                                         !! nodes on A's edges (A the coarser)
      integer :: rigid = 0             !! index of the rigid body that is side B (0: a surface)
      integer :: line = 0              !! deck line of the INTERFACE (or first) card
   end type interface_t

   !> A rigid body: a profile (polyline or circle) carried by a reference node,
   !! which belongs to no element and moves the profile by its displacement
   !! (translation only; the body does not rotate).  The profile's outward
   !! normal points away from the body: a polyline is listed with the body on
   !! its left, i.e. anticlockwise around the body like the edges of an element.
   type :: rigid_body_t
      integer :: shape = RIGID_POLYLINE
      integer :: node = 0                   !! reference node
      real(dp), allocatable :: xy(:, :)     !! (2, nvert) polyline vertices
      real(dp) :: centre(2) = 0.0_dp        !! circle
      real(dp) :: radius = 0.0_dp
      integer :: line = 0                   !! deck line of the RIGID card
   end type rigid_body_t

   !> A zero-length contact element between node a (body A, the slave side)
   !! and a point b of body B (the master side): node b itself (the paper's
   !! two-node spring), the surface of B interpolated from its nodes (averaged
   !! over the tributary zone of node a, see contact_pairing), or a point of
   !! a rigid profile moved by the rigid body's reference node.  The
   !! local axes (t, n) belong to body B, n points from B into A.  In every
   !! case the displacement of b is u_b = sum_k w(k) u(nodes(k)), k = 2..nn,
   !! so that the relative displacement u_a - u_b is linear in the pair's
   !! 2 nn dofs.
   type :: contact_pair_t
      integer :: node_a = 0
      integer :: node_b = 0                 !! node b; for a segment the master node nearest b,
                                            !! for a rigid profile the reference node
      integer :: iface = 1
      integer :: kind = PAIR_NODE           !! PAIR_NODE, PAIR_SEGMENT or PAIR_RIGID
      integer :: nn = 2                     !! nodes of the element: a, then the master nodes
      integer :: nodes(MAX_PAIR_NODES) = 0  !! (a, b) or (a, reference node)
                                            !! or (a, master nodes of B)
      real(dp) :: w(MAX_PAIR_NODES) = [1.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, &
                                       0.0_dp]  !! w(2:nn): weights of b
      real(dp) :: t(2) = [1.0_dp, 0.0_dp]   !! unit tangent (cos alpha, sin alpha), eq. (3.31)
      real(dp) :: n(2) = [0.0_dp, 1.0_dp]   !! unit normal, n = (-sin alpha, cos alpha)
      real(dp) :: g0 = 0.0_dp               !! initial gap along n, eq. (3.8)
      real(dp) :: g_point = huge(1.0_dp)    !! MATCHING SEGMENT: the gap at node a itself (g0 is
                                            !! averaged over its zone); huge otherwise
      real(dp) :: area = 0.0_dp             !! lumped contact area A_j, eqs.
                                            !! (3.22), (3.26), (A1)-(A6)
      real(dp) :: position(2) = 0.0_dp      !! coordinates of point b (node
                                            !! b for node-to-node; for output)
      ! scales of the ideal (augmented Lagrangian) contact, from the definition
      real(dp) :: length = 0.0_dp           !! length of the contact elements
                                            !! at the pair (mean of its edges)
      real(dp) :: share = 0.0_dp            !! equal share of the areas of those
                                            !! edges (> 0 also on the axis)
      real(dp) :: estar = 0.0_dp            !! contact modulus 1/((1-nu_a^2)/E_a + (1-nu_b^2)/E_b)
      integer :: line = 0                   !! deck line that created the pair
   end type contact_pair_t

   !> Options of the contact algorithm (SPEC §4.5).  The default update is
   !! the return to the laws (Newton), which ends every increment on the laws;
   !! the paper's explicit update is SCHEME INCREMENTAL.
   type :: contact_options_t
      integer :: update = UPDATE_RETURN
      logical :: first_iterate = .false.    !! iterate the first increment with the secant
      integer :: max_repeats = 30           !! cap on repeats of one increment
      real(dp) :: p_start = -1.0_dp         !! starting pressure p_m (< 0: from the first increment)
      integer :: n_start = 0                !! close the n_start pairs of smallest
                                            !! gap initially (0: by gap)
      real(dp) :: gap_tol = -1.0_dp         !! pairs with g0 <= gap_tol start
                                            !! closed (< 0: 1e-9 x model size)
      real(dp) :: tol_residual = 1.0e-10_dp !! relative out-of-balance force accepted by RETURN
      real(dp) :: tol_displacement = 1.0e-8_dp  !! relative last correction accepted by RETURN
      logical :: modified = .false.         !! RETURN with the stiffness of the
                                            !! first solution (modified Newton)
      real(dp) :: p_min_ratio = 1.0e-3_dp   !! floor of a newly closed pair's secant pressure, x p_m
      integer :: newly_closed = NEWCLOSED_SECANT   !! stiffness rule for a pair that closes
      ! ideal contact (augmented Lagrangian, SPEC reference model)
      real(dp) :: aug_factor = 100.0_dp     !! penalty per unit area = aug_factor E* / length
      real(dp) :: aug_tol = 1.0e-6_dp       !! penetration and stick drift
                                            !! accepted, x smallest length
      logical :: repeats_given = .false.    !! REPEATS card given (else a default per law)
   end type contact_options_t

   !> Everything the deck says about contact.
   type :: contact_def_t
      logical :: active = .false.
      type(interface_t), allocatable :: ifaces(:)
      type(contact_pair_t), allocatable :: pairs(:)
      type(rigid_body_t), allocatable :: rigids(:)
      type(contact_options_t) :: opts
   end type contact_def_t

contains

   pure function units_name(u) result(s)
      integer, intent(in) :: u
      character(len=:), allocatable :: s
      select case (u)
      case (UNITS_KGF_UM)
         s = 'KGF_UM (cn in µm/(kgf/cm2)^m)'
      case (UNITS_N_UM)
         s = 'N_UM (cn in µm/(N/mm2)^m)'
      case default
         s = 'MODEL (constants in model units)'
      end select
   end function units_name

   pure function friction_name(f) result(s)
      integer, intent(in) :: f
      character(len=:), allocatable :: s
      select case (f)
      case (FRICTION_NONE)
         s = 'NONE'
      case (FRICTION_COULOMB)
         s = 'COULOMB'
      case default
         s = 'FREDRIKSSON'
      end select
   end function friction_name

   pure function update_name(u) result(s)
      integer, intent(in) :: u
      character(len=:), allocatable :: s
      if (u == UPDATE_RETURN) then
         s = 'RETURN'
      else
         s = 'EXPLICIT'
      end if
   end function update_name

   pure function law_name(l) result(s)
      integer, intent(in) :: l
      character(len=:), allocatable :: s
      if (l == LAW_IDEAL) then
         s = 'IDEAL'
      else
         s = 'ROUGH'
      end if
   end function law_name

   pure function matching_name(mt, rigid) result(s)
      integer, intent(in) :: mt, rigid
      character(len=:), allocatable :: s
      if (rigid > 0) then
         s = 'RIGID'
      else if (mt == MATCH_SEGMENT) then
         s = 'SEGMENT'
      else
         s = 'NODE'
      end if
   end function matching_name

   pure function rigid_shape_name(k) result(s)
      integer, intent(in) :: k
      character(len=:), allocatable :: s
      if (k == RIGID_CIRCLE) then
         s = 'CIRCLE'
      else
         s = 'POLYLINE'
      end if
   end function rigid_shape_name

   pure function slip_name(u) result(s)
      integer, intent(in) :: u
      character(len=:), allocatable :: s
      if (u == SLIP_GROSS) then
         s = 'GROSS'
      else
         s = 'IRREVERSIBLE'
      end if
   end function slip_name
end module contact_types
