!> What each solver can take, in one table: one row per method (`solver_info`), read by the
!> `auto` rule and the device rule (veslide_solver), the memory estimate (veslide_memory) and the
!> input check (veslide_config), so that a method is refused for the same reason, in the same
!> words, wherever the refusal is made (`method_refusal`: at the input, before anything is built,
!> and at the solve).
!>
!> | method | operator       | contact laws | device | bytes per cell, host | on the device         |
!> |--------|----------------|--------------|--------|----------------------|-----------------------|
!> | pk     | symmetric only | hard wall    | no     | 16                   | -                     |
!> | bccg   | symmetric only | hard wall    | yes    | 36                   | 25                    |
!> | dr     | any            | hard wall    | yes    | 40 + 8 m             | 40 + 8 m              |
!> | pdr    | any            | hard wall    | yes    | 41 (+ 16 + 8 m)      | 33 or 41 (+ 24 + 8 m) |
!> | gcg    | any            | adhesive     | yes    | 86 (54 symmetric)    | 86 (54 symmetric)     |
!>
!> The operator is symmetric for an elastic solid or a solid at rest (`operator_symmetric`); a
!> viscoelastic solid in motion gives a non-symmetric one, which Polonsky-Keer and BCCG (conjugate
!> gradients) cannot take, on every grid with a mode the motion reaches (`motion_on_grid`): on a
!> grid of at most 2 cells along x, and along y too unless the motion is exactly along x, every
!> mode is the mean or a Nyquist line along the motion, which the kernel keeps real, and its
!> operator is symmetric after all. An interfacial shear on a compressible solid (&interface
!> shear_coefficient > 0, poisson < 1/2) makes it non-symmetric too, elastic or not, at any speed,
!> on every grid its direction reaches (`shear_symmetric`). The input refuses by these; the solve
!> reads the kernel's own symmetry (`kernel_t%symmetric`), the same verdict. Bytes per cell are a solver's own arrays
!> beyond the solve's (heights, kernel, FFT buffers, p, u, g: veslide_memory), measured peaks in
!> docs/solver-scaling.md:
!> pk 16 (the direction t and one influence column); bccg 36 (direction, operator, the transforms
!> of heights and pressure, the contact set); dr 40 + 8 m (z, the previous z and f, the transform
!> of h, the resolvent, Anderson's single-precision history of memory m, 5 by default); pdr 41
!> (bccg's fields with M = |K|, the resolvent's constant part), and 16 + 8 m more when Anderson
!> mixes its steps (m > 0; by default it does not). On the device: bccg 25 (the transforms of the
!> heights and of the pressure 16, the direction 8, the contact set 1; M is formed from K_d where
!> read, veslide_bccg_passes), pdr bccg's and the resolvent's constant part (33), and 8 more for
!> cuFFT's own work area where the device has room for it (then it keeps the CPU's arithmetic;
!> its lean layout otherwise, veslide_solver_pdr), with mixing 24 + 8 m more (Anderson's 16 and
!> cuFFT's own work area 8: u, which lends it otherwise, keeps f = y - x across transforms), dr
!> 40 + 8 m; cuFFT's work area is u's memory (veslide_contact's fields) but for those. Anderson
!> mixing there takes a memory of at most `device_max_memory`.
!> A new solver is a row here; a new contact law a column of `laws` (veslide_contact_law).
module veslide_solver_table
    use veslide_kinds, only: dp, radians
    use veslide_strings, only: str
    use veslide_contact_law, only: law_count, law_names, LAW_HARD_WALL, LAW_EXPONENTIAL, LAW_DUGDALE
    use veslide_solver_options, only: SOLVER_AUTO, SOLVER_PK, SOLVER_DR, SOLVER_BCCG, SOLVER_PDR, SOLVER_GCG, &
                                      solver_method_names
    use veslide_anderson_passes, only: device_max_memory
    implicit none
    private
    public :: solver_info_t, solver_info, solver_methods, operator_symmetric, motion_on_grid, shear_symmetric, &
              method_takes, &
              method_refusal, device_refusal, memory_refusal, solver_bytes_per_cell, runs_on_device

    !> What one method can take, and what it costs
    type :: solver_info_t
        integer :: method = 0                    !! SOLVER_* id
        logical :: symmetric_only = .false.      !! needs a symmetric operator
        logical :: laws(law_count) = .false.     !! the contact laws it takes (by LAW_* id)
        logical :: device = .false.              !! runs on the device
        logical :: mixes = .false.               !! takes Anderson mixing (its memory m)
        integer :: anderson_default = 0          !! m when the options leave it to the method (-1)
        real(dp) :: host_bytes = 0.0_dp          !! its own arrays on the host [bytes per cell]
        real(dp) :: device_bytes = 0.0_dp        !! on the device, where it runs there [bytes per cell]
        real(dp) :: mixing_bytes = 0.0_dp        !! more when it mixes (m > 0), besides 8 m [bytes per cell]
        real(dp) :: device_mixing_bytes = 0.0_dp !! the same on the device [bytes per cell]
        !> on the device, more without mixing where the device has room (cuFFT's own work area)
        real(dp) :: device_room_bytes = 0.0_dp
    end type solver_info_t

    !> The methods, in the order their alternatives are named
    integer, parameter :: solver_methods(5) = [SOLVER_BCCG, SOLVER_PDR, SOLVER_DR, SOLVER_PK, SOLVER_GCG]

contains

    !> The row of `method` (SOLVER_* id; an empty row for 'auto', which is a rule, not a method)
    pure function solver_info(method) result(row)
        integer, intent(in) :: method
        type(solver_info_t) :: row
        integer :: k
        logical, parameter :: hard_wall(law_count) = [(k == LAW_HARD_WALL, k=1, law_count)]
        logical, parameter :: adhesive(law_count) = [(k == LAW_EXPONENTIAL .or. k == LAW_DUGDALE, k=1, law_count)]
        select case (method)
        case (SOLVER_PK)
            row = solver_info_t(method=SOLVER_PK, symmetric_only=.true., laws=hard_wall, device=.false., &
                                host_bytes=16.0_dp)
        case (SOLVER_BCCG)
            row = solver_info_t(method=SOLVER_BCCG, symmetric_only=.true., laws=hard_wall, device=.true., &
                                host_bytes=36.0_dp, device_bytes=25.0_dp)
        case (SOLVER_DR)
            row = solver_info_t(method=SOLVER_DR, laws=hard_wall, device=.true., mixes=.true., anderson_default=5, &
                                host_bytes=40.0_dp, device_bytes=40.0_dp)
        case (SOLVER_PDR)
            row = solver_info_t(method=SOLVER_PDR, laws=hard_wall, device=.true., mixes=.true., anderson_default=0, &
                                host_bytes=41.0_dp, device_bytes=33.0_dp, mixing_bytes=16.0_dp, &
                                device_mixing_bytes=24.0_dp, device_room_bytes=8.0_dp)
        case (SOLVER_GCG)
            ! the heights, the gap, its search direction, A (g + h), the gradient and its
            ! preconditioned form (48), the free set and Dugdale's edge (2), the multiplier A on the
            ! half-spectrum (4); on a non-symmetric operator the splitting's z, x and heights and
            ! 1/K on the half-spectrum, 32 more: the estimate takes the larger (veslide_solver_gcg)
            row = solver_info_t(method=SOLVER_GCG, laws=adhesive, device=.true., host_bytes=86.0_dp, &
                                device_bytes=86.0_dp)
        case default
            row = solver_info_t()
        end select
    end function solver_info

    !> Is the operator of a solid `elastic` or not at the speeds `speeds` [m/s] (a case's, or every
    !> one of a study's) symmetric: an elastic solid, or one at rest at every speed
    pure logical function operator_symmetric(elastic, speeds) result(yes)
        logical, intent(in) :: elastic
        real(dp), intent(in) :: speeds(:)
        yes = elastic .or. all(speeds == 0.0_dp)
    end function operator_symmetric

    !> Does the motion at `speeds` [m/s] along `direction_deg` [degree] reach a mode of an nx x ny
    !> grid that makes a viscoelastic solid's discrete operator non-symmetric: a mode off the mean
    !> and the Nyquist lines along a component of the velocity that is not zero (nx >= 3 with a
    !> velocity along x, or ny >= 3 with one along y; the velocity as the kernel takes it,
    !> speed [cos, sin] of the direction in radians)? On the other grids the kernel's Nyquist
    !> averaging leaves every mode real.
    pure logical function motion_on_grid(nx, ny, speeds, direction_deg) result(yes)
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: speeds(:), direction_deg
        real(dp) :: th
        th = radians(direction_deg)
        yes = (nx >= 3 .and. any(speeds*cos(th) /= 0.0_dp)) .or. (ny >= 3 .and. any(speeds*sin(th) /= 0.0_dp))
    end function motion_on_grid

    !> Is the part of the operator an interfacial shear brings symmetric: its coupling `coupling`
    !> (beta mu_f, veslide_material's `coupling_beta` times &interface shear_coefficient) is 0, or
    !> its direction `direction_deg` [degree] (the velocity's, at any speed) reaches no mode of an
    !> nx x ny grid off the mean and the Nyquist lines (`motion_on_grid` of a unit speed), where
    !> the factor 1 - i beta mu_f (q.v_hat)/|q| is averaged to 1
    pure logical function shear_symmetric(coupling, nx, ny, direction_deg) result(yes)
        real(dp), intent(in) :: coupling, direction_deg
        integer, intent(in) :: nx, ny
        yes = coupling == 0.0_dp .or. .not. motion_on_grid(nx, ny, [1.0_dp], direction_deg)
    end function shear_symmetric

    !> Does `method` take a case whose operator is `symmetric` or not, with the contact law `law`
    !> (LAW_* id)? 'auto' takes what any method takes
    pure logical function method_takes(method, symmetric, law) result(yes)
        integer, intent(in) :: method, law
        logical, intent(in) :: symmetric
        integer :: k
        if (method == SOLVER_AUTO) then
            yes = any([(len(refusal_reason(solver_methods(k), symmetric, law)) == 0, k=1, size(solver_methods))])
        else
            yes = len(refusal_reason(method, symmetric, law)) == 0
        end if
    end function method_takes

    !> Does `method` run on the device ('auto': every method its rule picks does)?
    pure logical function runs_on_device(method) result(yes)
        integer, intent(in) :: method
        type(solver_info_t) :: row
        yes = .true.
        if (method == SOLVER_AUTO) return
        row = solver_info(method)
        yes = row%device
    end function runs_on_device

    !> Why `method` cannot take a case whose operator is `symmetric` or not, with the contact law
    !> `law`: the message naming &solver method, the reason and the methods that would take the
    !> case; empty when it can
    pure function method_refusal(method, symmetric, law) result(message)
        integer, intent(in) :: method, law
        logical, intent(in) :: symmetric
        character(len=:), allocatable :: message
        character(len=:), allocatable :: why
        integer :: k
        message = ''
        if (method == SOLVER_AUTO) then
            ! (dr takes any operator: what no method takes is the law)
            if (method_takes(SOLVER_AUTO, symmetric, law)) return
            message = "&solver method = 'auto' finds no method that takes the contact law "//law_text(law)
            if (.not. symmetric .and. method_takes(SOLVER_AUTO, .true., law)) message = message// &
                " on a non-symmetric operator (a viscoelastic solid in motion): the methods for it ("// &
                alternatives([(method_takes(solver_methods(k), .true., law), k=1, size(solver_methods))])// &
                ") need an elastic solid or one at rest (docs/adhesion.md)"
            return
        end if
        why = refusal_reason(method, symmetric, law)
        if (len(why) == 0) return
        message = "&solver method = '"//trim(solver_method_names(method))//"' "//why//"; methods that take this"// &
                  " case: "//alternatives([(method_takes(solver_methods(k), symmetric, law), k=1, size(solver_methods))])
    end function method_refusal

    !> Why `method` cannot run on the device (a solve there asked for by &solver device = 'gpu'):
    !> the message naming &solver method and the methods that would take the case there (its
    !> operator `symmetric` or not, its contact law `law`); empty when it can
    pure function device_refusal(method, symmetric, law) result(message)
        integer, intent(in) :: method, law
        logical, intent(in) :: symmetric
        character(len=:), allocatable :: message
        integer :: k
        message = ''
        if (runs_on_device(method)) return
        message = "&solver method = '"//trim(solver_method_names(method))//"' does not run on the device;"// &
                  " methods that take this case there: "// &
                  alternatives([(method_takes(solver_methods(k), symmetric, law) .and. &
                                 runs_on_device(solver_methods(k)), k=1, size(solver_methods))])// &
                  " (or &solver device = 'cpu')"
    end function device_refusal

    !> Why the Anderson memory `memory` (the options': negative for each method's own) cannot
    !> mix `method`'s steps on the device; empty when it can
    pure function memory_refusal(method, memory) result(message)
        integer, intent(in) :: method, memory
        character(len=:), allocatable :: message
        type(solver_info_t) :: row
        message = ''
        row = solver_info(method)
        if (.not. row%mixes .or. memory <= device_max_memory) return
        message = "&solver anderson_memory = "//str(memory)//" does not run on the device (0.."// &
                  str(device_max_memory)//" does, and -1, each method's own), or set &solver device = 'cpu'"
    end function memory_refusal

    !> Bytes per cell of `method`'s own arrays (on the device when `device`: at least, or with
    !> `room`, where the device has room for all it takes) with Anderson memory `memory` (the
    !> options': negative for the method's own)
    pure real(dp) function solver_bytes_per_cell(method, memory, device, room) result(b)
        integer, intent(in) :: method, memory
        logical, intent(in) :: device
        logical, intent(in), optional :: room
        type(solver_info_t) :: row
        integer :: m
        logical :: room_
        room_ = .false.; if (present(room)) room_ = room
        row = solver_info(method)
        b = merge(row%device_bytes, row%host_bytes, device)
        m = memory
        if (m < 0) m = row%anderson_default
        if (.not. row%mixes) m = 0
        if (device .and. room_ .and. m == 0) b = b + row%device_room_bytes
        if (.not. row%mixes) return
        if (m > 0) b = b + merge(row%device_mixing_bytes, row%mixing_bytes, device) + 8*m
    end function solver_bytes_per_cell

    !> The reason alone (empty when `method` takes the case)
    pure function refusal_reason(method, symmetric, law) result(why)
        integer, intent(in) :: method, law
        logical, intent(in) :: symmetric
        character(len=:), allocatable :: why
        type(solver_info_t) :: row
        row = solver_info(method)
        why = ''
        if (law < 1 .or. law > law_count) then
            why = "does not take the contact law "//law_text(law)
        else if (.not. row%laws(law)) then
            why = "does not take the contact law "//law_text(law)
        else if (row%symmetric_only .and. .not. symmetric) then
            why = "needs a symmetric operator (an elastic solid, or one at rest, without interfacial shear): the"// &
                  " operator of a viscoelastic solid in motion (&motion speed_m_s or &sweep speeds above 0), or of"// &
                  " any solid of poisson below 0.5 with &interface shear_coefficient above 0, is not symmetric"
        end if
    end function refusal_reason

    !> The contact law of id `law` by name ("'hard_wall'"), or by its id when it has none
    pure function law_text(law) result(text)
        integer, intent(in) :: law
        character(len=:), allocatable :: text
        if (law >= 1 .and. law <= law_count) then
            text = "'"//trim(law_names(law))//"'"
        else
            text = "of id "//str(law)
        end if
    end function law_text

    !> "'auto', 'pdr' and 'dr'": the methods marked in `takes` (in the order of solver_methods),
    !> with 'auto' first when any is
    pure function alternatives(takes) result(text)
        logical, intent(in) :: takes(:)
        character(len=:), allocatable :: text
        integer :: k, n, total
        total = count(takes)
        if (total == 0) then
            text = "none"; return
        end if
        text = "'auto'"
        n = 1
        do k = 1, size(takes)
            if (.not. takes(k)) cycle
            n = n + 1
            if (n == total + 1) then
                text = text//" and "
            else
                text = text//", "
            end if
            text = text//"'"//trim(solver_method_names(solver_methods(k)))//"'"
        end do
    end function alternatives

end module veslide_solver_table
