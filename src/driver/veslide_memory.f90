!> The memory a case or a study will need, estimated before anything is allocated, so that a grid
!> too large for the machine is refused in one line instead of failing at an allocation or in the
!> out-of-memory killer.
!>
!> The estimate is the largest of the phases of a run, in bytes per grid cell (N = nx ny), plus a
!> fixed allowance for the libraries, the FFTW plans and the output. Resident during a solve: the
!> heights (8) and the kernel (8; the contact problem holds the case's, not copies), the FFT
!> buffers (16), the solution p, u, g (24); then the solver's own arrays, its row of the solver
!> table (veslide_solver_table: measured peaks at 512^2 and 1024^2 in docs/solver-scaling.md;
!> pk 16, bccg 36, dr 40 + 8 m, pdr 41 and 16 + 8 m more when it mixes). Surface generation is
!> transient (16 for its own transform), and the splitting's last step holds one more field (8)
!> in a temporary. Aliased
!> kernels hold 32 while they are summed. Analyses after the solve:
!> slope force 8, patches 32, Persson 24. A study adds one kernel per speed (8 each), the previous
!> speed's p and g (16) and the case's copies of heights and kernel (16). The method is the one
!> veslide_solver will run (`planned_methods`: for 'auto' the same rule, the largest of pdr and
!> dr when the material's Einf/E0 does not decide the operator's spread before it is built).
!>
!> A solve on the device (veslide_device) holds its solver's arrays there, not on the host: the
!> host keeps the case (heights, kernel, FFT buffers for the analyses, p, u, g) and the device
!> holds, per cell, the heights (8), the kernel's multiplier (8), the transform's buffers (16), p,
!> u, g (24), and the solver's own arrays there (the table's: bccg 25, dr 40 + 8 m, pdr 33 and
!> 24 + 8 m more when it mixes). cuFFT's work area (at most 8 per cell, one for both plans) is
!> u's memory, lent to the transform, except for pdr, whose row counts it (8 of its mixing's 24;
!> without mixing pdr takes its own where the device has room for it, `room`, else lends u: the
!> estimate, which the refusal reads, is what it needs at least). Before anything is built the case's method is checked against the device it
!> will run on (`size_and_check_memory`, the solver table's refusal).
module veslide_memory
    use veslide_kinds, only: dp, i8
    use veslide_error, only: error_t, fatal_error, add_context
    use veslide_strings, only: str
    use veslide_case_data, only: case_spec_t
    use veslide_kernel, only: KERNEL_SPECTRAL
    use veslide_solver, only: planned_methods, auto_takes_device, check_device_choice
    use veslide_solver_options, only: DEVICE_GPU, DEVICE_AUTO
    use veslide_solver_table, only: solver_bytes_per_cell, operator_symmetric, motion_on_grid, runs_on_device, &
                                    device_refusal, memory_refusal, shear_symmetric
    use veslide_material, only: coupling_beta
    use veslide_device, only: device_info_t, device_info, device_memory
    use veslide_system, only: available_memory_bytes
    implicit none
    private
    public :: memory_estimate_bytes, device_estimate_bytes, device_bytes_per_cell, format_gib, size_and_check_memory, case_memory, &
              case_on_device

    !> Libraries, FFTW plans, HDF5 buffers and the program itself [bytes]
    integer(i8), parameter :: fixed_bytes = 16_i8*1024*1024
    !> On the device: the runtime's own and the row partials [bytes]
    integer(i8), parameter :: device_fixed_bytes = 64_i8*1024*1024

contains

    !> Peak memory of the case `spec` on its grid [bytes]; of a study when its `speeds` are given
    !> (one kernel held per speed); with `ranks`, of one of that many processes sharing the grid
    !> (its rows, plus FFTW's MPI transposes: one more complex half-spectrum of its share, 8 bytes
    !> per cell). With `device`, a case solved on the device: the host's share (its solver's
    !> arrays are there)
    pure integer(i8) function memory_estimate_bytes(spec, ranks, device, speeds) result(bytes)
        type(case_spec_t), intent(in) :: spec
        integer, intent(in), optional :: ranks
        logical, intent(in), optional :: device
        real(dp), intent(in), optional :: speeds(:)
        real(dp) :: n, solve, solver, analysis, kernel_build, study, per_cell
        n = real(spec%nx, dp)*real(spec%ny, dp)
        solve = 8 + 8 + 16 + 24
        solver = solver_bytes(spec, .false., speeds)
        if (present(device)) then
            if (device) solver = 0
        end if
        analysis = 8
        if (spec%analysis%patches) analysis = analysis + 32
        if (spec%analysis%persson) analysis = analysis + 24
        kernel_build = 8 + 16
        if (spec%kernel_name() == 'collocation-alias' .or. spec%kernel_name() == 'galerkin') kernel_build = 8 + 32
        study = 0
        if (present(speeds)) study = 8*max(1, size(speeds)) + 16 + 16
        per_cell = solve + max(solver, analysis, kernel_build, 16.0_dp) + study
        if (present(ranks)) then
            if (ranks > 1) then
                per_cell = per_cell + 8
                n = n/ranks
            end if
        end if
        bytes = fixed_bytes + int(per_cell*n, i8)
    end function memory_estimate_bytes

    !> Device memory a solve of the case `spec` (a study of its `speeds`) holds at its peak
    !> [bytes] (veslide_device: what the heading lists): at least (what it needs: pdr in its lean
    !> layout), or with `room`, where the device has room for all it takes
    pure integer(i8) function device_estimate_bytes(spec, speeds, room) result(bytes)
        type(case_spec_t), intent(in) :: spec
        real(dp), intent(in), optional :: speeds(:)
        logical, intent(in), optional :: room
        real(dp) :: n
        n = real(spec%nx, dp)*real(spec%ny, dp)
        bytes = device_fixed_bytes + int(device_bytes_per_cell(spec, speeds, room)*n, i8)
    end function device_estimate_bytes

    !> The device's bytes per cell of `device_estimate_bytes` (without its fixed allowance)
    pure real(dp) function device_bytes_per_cell(spec, speeds, room) result(per_cell)
        type(case_spec_t), intent(in) :: spec
        real(dp), intent(in), optional :: speeds(:)
        logical, intent(in), optional :: room
        per_cell = 8 + 8 + 16 + 24 + solver_bytes(spec, .true., speeds, room)
    end function device_bytes_per_cell

    !> The bytes per cell of the solver the case `spec` runs (the largest of those veslide_solver
    !> may run, `planned_methods`), on the host or the `device`: the solver table's. The kernel is
    !> symmetric for an elastic solid or a solid at rest (every speed of a study 0).
    pure real(dp) function solver_bytes(spec, device, speeds, room) result(b)
        type(case_spec_t), intent(in) :: spec
        logical, intent(in) :: device
        real(dp), intent(in), optional :: speeds(:)
        logical, intent(in), optional :: room
        integer, allocatable :: methods(:)
        logical :: symmetric
        real(dp) :: bound
        integer :: k
        symmetric = case_symmetric(spec, speeds)
        ! the operator's spread is at most Einf/E0 for the spectral kernel of a half-space, times
        ! sqrt(1 + (beta mu_f)^2) with an interfacial shear (|1 - i beta mu_f (q.v_hat)/|q|| within a
        ! shell); unknown for the other variants and for a layer (whose factor varies across a
        ! shell of |q|)
        bound = huge(1.0_dp)
        if (spec%kernel_variant == KERNEL_SPECTRAL .and. spec%material%solid%thickness_m == 0.0_dp .and. &
            spec%material%solid%e0_pa > 0.0_dp) then
            bound = spec%material%solid%einf_pa/spec%material%solid%e0_pa
            if (spec%shear_coefficient > 0.0_dp) bound = bound* &
                sqrt(1.0_dp + (coupling_beta(spec%material%solid%poisson)*spec%shear_coefficient)**2)
        end if
        methods = planned_methods(spec%solver%method, symmetric, real(spec%nx, dp)*real(spec%ny, dp), bound, &
                                  spec%law%kind)
        b = 0
        do k = 1, size(methods)
            b = max(b, solver_bytes_per_cell(methods(k), spec%solver%anderson_memory, device, room))
        end do
    end function solver_bytes

    !> Is the operator of the case `spec` (a study of its `speeds`) symmetric: an elastic solid, or
    !> one at rest at every speed, without an interfacial shear on a compressible solid
    !> (veslide_solver_table). With `on_grid`, also on a grid no mode of which the motion (the
    !> shear's direction) reaches (`motion_on_grid`, `shear_symmetric`: the refusals' rule, the
    !> input's and the solve's); without, the solid's alone: the estimate sizes those few grids
    !> (at most 2 cells along the motion) for the methods of a non-symmetric operator, more than
    !> 'auto' takes there
    pure logical function case_symmetric(spec, speeds, on_grid) result(yes)
        type(case_spec_t), intent(in) :: spec
        real(dp), intent(in), optional :: speeds(:)
        logical, intent(in), optional :: on_grid
        real(dp), allocatable :: v(:)
        real(dp) :: coupling
        if (present(speeds)) then
            v = speeds
        else
            v = [spec%speed_m_s]
        end if
        yes = operator_symmetric(spec%material%model == 'elastic', v)
        coupling = coupling_beta(spec%material%solid%poisson)*spec%shear_coefficient
        if (present(on_grid)) then
            if (on_grid) then
                yes = (yes .or. .not. motion_on_grid(spec%nx, spec%ny, v, spec%direction_deg)) .and. &
                      shear_symmetric(coupling, spec%nx, spec%ny, spec%direction_deg)
                return
            end if
        end if
        yes = yes .and. coupling == 0.0_dp
    end function case_symmetric

    !> Will the case `spec` be solved on the device (on `ranks` processes: never shared)?
    logical function case_on_device(spec, ranks) result(yes)
        type(case_spec_t), intent(in) :: spec
        integer, intent(in), optional :: ranks
        yes = .false.
        if (present(ranks)) then
            if (ranks > 1) return
        end if
        select case (spec%solver%device)
        case (DEVICE_GPU)
            yes = runs_on_device(spec%solver%method)     ! (what it does not run is refused before)
        case (DEVICE_AUTO)
            yes = auto_takes_device(spec%solver%method, spec%solver%anderson_memory, .false.)
        end select
    end function case_on_device

    !> The memory the case `spec` (a study of its `speeds`) will need, per process when `ranks`
    !> processes share its grid [bytes], before anything is allocated; with `device_estimate`, what
    !> a solve on the device holds there (0: the case is solved on the CPU)
    subroutine case_memory(spec, estimate, ranks, device_estimate, speeds)
        type(case_spec_t), intent(in) :: spec
        integer(i8), intent(out) :: estimate
        integer, intent(in), optional :: ranks
        integer(i8), intent(out), optional :: device_estimate
        real(dp), intent(in), optional :: speeds(:)
        logical :: device
        if (present(device_estimate)) device_estimate = 0
        device = case_on_device(spec, ranks)
        estimate = memory_estimate_bytes(spec, ranks, device, speeds)
        if (device .and. present(device_estimate)) device_estimate = device_estimate_bytes(spec, speeds)
    end subroutine case_memory

    !> Before anything is allocated: the memory the run will need against what the process may
    !> use; refused in one line naming &grid nx, ny (or the height file) when it does not fit.
    !> Returns the estimate. On a grid shared by `ranks` processes, `node_ranks` of them on this
    !> machine, the estimate is one process's share and the memory free on the machine is shared
    !> among those. A case solved on the device is refused, in the same way, when the device's
    !> estimate (`device_estimate`, 0 for a case on the CPU) exceeds the device's free memory. A
    !> study passes its `speeds`.
    subroutine size_and_check_memory(spec, estimate, error, ranks, node_ranks, device_estimate, speeds)
        type(case_spec_t), intent(in) :: spec
        integer(i8), intent(out) :: estimate
        type(error_t), allocatable, intent(out) :: error
        integer, intent(in), optional :: ranks, node_ranks
        integer(i8), intent(out), optional :: device_estimate
        real(dp), intent(in), optional :: speeds(:)
        integer(i8) :: available, dev
        integer :: ranks_, node_ranks_
        character(len=:), allocatable :: what, who
        ranks_ = 1; if (present(ranks)) ranks_ = max(1, ranks)
        node_ranks_ = 1; if (present(node_ranks)) node_ranks_ = max(1, node_ranks)
        estimate = 0
        if (present(device_estimate)) device_estimate = 0
        call check_device_choice(spec%solver%device, error)
        if (.not. allocated(error) .and. spec%solver%device == DEVICE_GPU .and. ranks_ == 1) &
            call check_method_on_device(spec, error, speeds)
        call add_context(error, "veslide: "//spec%input_path//": ")
        if (allocated(error)) return
        what = "&grid nx, ny = "
        if (spec%surface%kind == 'file') what = "&surface file '"//spec%surface%file//"' of "
        call case_memory(spec, estimate, ranks_, dev, speeds)
        if (present(device_estimate)) device_estimate = dev
        if (dev > 0) then
            call check_device_memory(spec, dev, error); if (allocated(error)) return
        end if
        available = available_memory_bytes()
        if (available >= 0) available = available/node_ranks_
        if (available >= 0 .and. estimate > available) then
            what = what//str(spec%nx)//" x "//str(spec%ny)
            who = "this process (free memory, ulimit and cgroup limits)"
            if (ranks_ > 1) then
                what = what//" on "//str(ranks_)//" processes"
                who = "each of the "//str(node_ranks_)//" processes on this machine (its share of the free memory,"// &
                      " ulimit and cgroup limits)"
            end if
            call fatal_error(error, "veslide: "//spec%input_path//": "//what//" needs about "//format_gib(estimate)// &
                " of memory per process, and "//format_gib(available)//" is available to "//who// &
                ": choose a smaller &grid nx, ny, use more processes, or run where more memory is free")
        end if
    end subroutine size_and_check_memory

    !> The case's method refused where the device does not run it (&solver device = 'gpu', before
    !> anything is built: the solver table's refusal, as the solve's)
    subroutine check_method_on_device(spec, error, speeds)
        type(case_spec_t), intent(in) :: spec
        type(error_t), allocatable, intent(out) :: error
        real(dp), intent(in), optional :: speeds(:)
        character(len=:), allocatable :: why
        why = device_refusal(spec%solver%method, case_symmetric(spec, speeds, on_grid=.true.), spec%law%kind)
        if (len(why) == 0) why = memory_refusal(spec%solver%method, spec%solver%anderson_memory)
        if (len(why) > 0) call fatal_error(error, "veslide:solver: "//why)
    end subroutine check_method_on_device

    !> The device estimate `dev` against the device's free memory (refused in one line naming both)
    subroutine check_device_memory(spec, dev, error)
        type(case_spec_t), intent(in) :: spec
        integer(i8), intent(in) :: dev
        type(error_t), allocatable, intent(out) :: error
        type(device_info_t) :: info
        real(dp) :: free_b, total_b
        call device_memory(free_b, total_b, error); if (allocated(error)) return
        if (free_b < 0.0_dp .or. real(dev, dp) <= free_b) return
        call device_info(info, error); if (allocated(error)) return
        call fatal_error(error, "veslide: "//spec%input_path//": &grid nx, ny = "//str(spec%nx)//" x "// &
            str(spec%ny)//" needs about "//format_gib(dev)//" of device memory, and "// &
            format_gib(int(free_b, i8))//" is free on the "//info%name//" (of "//format_gib(int(total_b, i8))// &
            "): choose a smaller &grid nx, ny, a device with more memory, or &solver device = 'cpu'")
    end subroutine check_device_memory

    !> "12.34 GiB"
    pure function format_gib(bytes) result(s)
        integer(i8), intent(in) :: bytes
        character(len=:), allocatable :: s
        character(len=32) :: buf
        write (buf, '(f0.2," GiB")') real(bytes, dp)/1024.0_dp**3
        s = trim(buf)
        if (s(1:1) == '.') s = '0'//s
    end function format_gib

end module veslide_memory
