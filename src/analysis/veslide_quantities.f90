!> The named results of a case, each defined once with its units: the list that the HDF5 case
!> group (/scalars, /anisotropy, /patches), the /summary row of a study, the ensemble statistics
!> and the printed summary all read.
!>
!> A scalar is a `quantity_t` (name, units, value, integer or real, axial angle or not); arrays
!> (tensors, polar samples) are `array_t`. The definitions of derived quantities live here, as
!> procedures that append to a `results_t` list: forces and friction (`add_force_quantities`),
!> the solver report (`add_solver_quantities`). A new output scalar is one `add` line.
module veslide_quantities
    use veslide_kinds, only: dp, pi, radians
    use veslide_contact, only: contact_state_t
    implicit none
    private
    public :: quantity_t, array_t, results_t, add_force_quantities, add_solver_quantities, axial_of
    public :: AXIAL_NONE, AXIAL_HALF_TURN, AXIAL_SYMMETRIC

    !> How an angle averages over seeds: not an angle, an axis in [0, pi), an axis in (-pi/2, pi/2]
    integer, parameter :: AXIAL_NONE = 0, AXIAL_HALF_TURN = 1, AXIAL_SYMMETRIC = 2

    type :: quantity_t
        character(len=:), allocatable :: name    !! HDF5 name under /scalars and /summary column
        character(len=:), allocatable :: units   !! SI units ('-' for none)
        real(dp) :: value = 0.0_dp
        logical :: is_integer = .false.          !! stored as a 64-bit integer
        integer :: axial = AXIAL_NONE            !! AXIAL_* : how it averages over seeds
    end type quantity_t

    type :: array_t
        character(len=:), allocatable :: path    !! HDF5 path below the case group, e.g. '/anisotropy/theta_rad'
        character(len=:), allocatable :: units
        character(len=:), allocatable :: layout  !! 'layout' attribute ('' for none)
        real(dp), allocatable :: values(:)
    end type array_t

    type :: results_t
        type(quantity_t), allocatable :: scalars(:)
        type(array_t), allocatable :: arrays(:)
        integer :: n = 0, na = 0
    contains
        procedure :: add => results_add
        procedure :: add_array => results_add_array
        procedure :: get => results_get
        procedure :: has => results_has
        procedure :: trim => results_trim
    end type results_t

contains

    !> Append a scalar
    pure subroutine results_add(self, name, value, units, is_integer, axial)
        class(results_t), intent(inout) :: self
        character(len=*), intent(in) :: name, units
        real(dp), intent(in) :: value
        logical, intent(in), optional :: is_integer
        integer, intent(in), optional :: axial
        type(quantity_t), allocatable :: tmp(:)
        if (.not. allocated(self%scalars)) allocate (self%scalars(16))
        if (self%n == size(self%scalars)) then
            allocate (tmp(2*self%n)); tmp(1:self%n) = self%scalars
            call move_alloc(tmp, self%scalars)
        end if
        self%n = self%n + 1
        associate (q => self%scalars(self%n))
            q%name = name; q%units = units; q%value = value
            q%is_integer = .false.; if (present(is_integer)) q%is_integer = is_integer
            q%axial = axial_of(name); if (present(axial)) q%axial = axial
        end associate
    end subroutine results_add

    !> Append an array under `path` (below the case group)
    pure subroutine results_add_array(self, path, values, units, layout)
        class(results_t), intent(inout) :: self
        character(len=*), intent(in) :: path, units
        real(dp), intent(in) :: values(:)
        character(len=*), intent(in), optional :: layout
        type(array_t), allocatable :: tmp(:)
        if (.not. allocated(self%arrays)) allocate (self%arrays(8))
        if (self%na == size(self%arrays)) then
            allocate (tmp(2*self%na)); tmp(1:self%na) = self%arrays
            call move_alloc(tmp, self%arrays)
        end if
        self%na = self%na + 1
        associate (a => self%arrays(self%na))
            a%path = path; a%units = units; a%values = values
            a%layout = ''; if (present(layout)) a%layout = layout
        end associate
    end subroutine results_add_array

    !> How the quantity `name` averages over seeds: the directions of axes are angles modulo pi,
    !> theta in [0, pi) (of the slope tensors and of the patches), phi of eq. (16) in (-pi/2, pi/2]
    pure integer function axial_of(name) result(axial)
        character(len=*), intent(in) :: name
        axial = AXIAL_NONE
        select case (name)
        case ('theta_s_rad', 'theta_d_rad', 'patch_theta_rad')
            axial = AXIAL_HALF_TURN
        case ('phi_rad')
            axial = AXIAL_SYMMETRIC
        end select
    end function axial_of

    !> Value of the scalar `name` (huge() when absent; see `has`)
    pure real(dp) function results_get(self, name) result(v)
        class(results_t), intent(in) :: self
        character(len=*), intent(in) :: name
        integer :: k
        v = huge(1.0_dp)
        do k = 1, self%n
            if (self%scalars(k)%name == name) then
                v = self%scalars(k)%value; return
            end if
        end do
    end function results_get

    pure logical function results_has(self, name) result(yes)
        class(results_t), intent(in) :: self
        character(len=*), intent(in) :: name
        integer :: k
        yes = .false.
        do k = 1, self%n
            if (self%scalars(k)%name == name) yes = .true.
        end do
    end function results_has

    !> Shrink the lists to their lengths (scalars(1:n), arrays(1:na))
    pure subroutine results_trim(self)
        class(results_t), intent(inout) :: self
        if (.not. allocated(self%scalars)) allocate (self%scalars(0))
        if (.not. allocated(self%arrays)) allocate (self%arrays(0))
        self%scalars = self%scalars(1:self%n)
        self%arrays = self%arrays(1:self%na)
    end subroutine results_trim

    !> Forces of the solid on the rigid surface per unit nominal area, and what follows from them:
    !>   friction_force_pa = -F.v_hat, friction_coefficient = -F.v_hat/p_mean (> 0 against the motion),
    !>   lateral_force_pa = F.(z_hat x v_hat), lateral_force_ratio = F.(z_hat x v_hat)/p_mean,
    !>   force_x_pa, force_y_pa, friction_coefficient_slope = -<p grad h>.v_hat/p_mean (the check
    !>   estimator) and dissipated_power_w_m2 = -F.v.
    !> v_hat is the direction `direction_deg` of v (also at v = 0, where all vanish).
    pure subroutine add_force_quantities(r, force_pa, slope_force_pa, velocity_m_s, direction_deg, p_mean)
        type(results_t), intent(inout) :: r
        real(dp), intent(in) :: force_pa(2), slope_force_pa(2), velocity_m_s(2), direction_deg, p_mean
        real(dp) :: vhat(2), lat(2)
        vhat = [cos(radians(direction_deg)), sin(radians(direction_deg))]
        lat = [-vhat(2), vhat(1)]
        call r%add('friction_force_pa', -dot_product(force_pa, vhat), 'Pa')
        call r%add('friction_coefficient', -dot_product(force_pa, vhat)/p_mean, '-')
        call r%add('lateral_force_pa', dot_product(force_pa, lat), 'Pa')
        call r%add('lateral_force_ratio', dot_product(force_pa, lat)/p_mean, '-')
        call r%add('force_x_pa', force_pa(1), 'Pa')
        call r%add('force_y_pa', force_pa(2), 'Pa')
        call r%add('friction_coefficient_slope', -dot_product(slope_force_pa, vhat)/p_mean, '-')
        call r%add('dissipated_power_w_m2', -dot_product(force_pa, velocity_m_s), 'W/m^2')
    end subroutine add_force_quantities

    !> The solver's report: iterations, work, convergence and the four residual measures
    pure subroutine add_solver_quantities(r, state, tolerance)
        type(results_t), intent(inout) :: r
        type(contact_state_t), intent(in) :: state
        real(dp), intent(in) :: tolerance
        call r%add('iterations', real(state%iterations, dp), '-', is_integer=.true.)
        call r%add('operator_applications', real(state%operator_applications, dp), '-', is_integer=.true.)
        call r%add('converged', merge(1.0_dp, 0.0_dp, state%converged), '-', is_integer=.true.)
        call r%add('residual', state%residual, '-')
        call r%add('penetration', state%penetration, '-')
        call r%add('complementarity', state%complementarity, '-')
        call r%add('negative_pressure', state%negative_pressure, '-')
        call r%add('load_error', state%load_error, '-')
        call r%add('tolerance', tolerance, '-')
    end subroutine add_solver_quantities

end module veslide_quantities
