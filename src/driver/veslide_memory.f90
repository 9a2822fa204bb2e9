!> The memory a case or a study will need, estimated before anything is allocated, so that a grid
!> too large for the machine is refused in one line instead of failing at an allocation or in the
!> out-of-memory killer.
!>
!> The estimate is the largest of the phases of a run, in bytes per grid cell (N = nx ny), plus a
!> fixed allowance for the libraries, the FFTW plans and the output. Resident during a solve: the
!> heights (8) and the kernel (8; the contact problem holds the case's, not copies), the FFT
!> buffers (16), the solution p, u, g (24); then per solver (measured peaks at
!> 512^2 and 1024^2 in docs/solver-scaling.md): bccg 36 (direction, operator, the transforms of
!> heights and pressure, the contact set; the pressure is solved in place); the splitting dr 40 + 8 m
!> (z, the previous z and f, the transform of h, the resolvent, and Anderson's single-precision
!> history of memory m, 5 by default); pdr 41 (bccg's fields with M = |K|, the resolvent's
!> constant part; y, z and f live in the state's p, g and u, K is the kernel's own, borrowed),
!> and 16 + 8 m more when Anderson mixes its steps (m > 0; by default it does not); Polonsky-Keer
!> 16 (t and one influence column). `auto` is taken as bccg for a symmetric kernel and as pdr
!> from 256^2 cells up (dr below). Surface generation is transient (16 for its
!> own transform), and the splitting's last step holds one more field (8) in a temporary. Aliased
!> kernels hold 32 while they are summed. Analyses after the solve:
!> slope force 8, patches 32, Persson 24. A study adds one kernel per speed (8 each), the previous
!> speed's p and g (16) and the case's copies of heights and kernel (16).
!>
!> A solve on the device (veslide_device) holds its solver's arrays there, not on the host: the
!> host keeps the case (heights, kernel, FFT buffers for the analyses, p, u, g) and the device
!> holds, per cell, the heights (8), the kernel's multiplier (8), the transform's buffers (16), p,
!> u, g (24), and per solver: bccg 29 (M 4, the transforms of the heights and of the pressure 16,
!> the direction 8, the contact set 1), pdr bccg's and the resolvent's constant part (37; with
!> Anderson mixing 16 + 8 m more), dr
!> 40 + 8 m (z, the previous z and f, the transform of h, the resolvent's multiplier, the history
!> in single precision); plus cuFFT's work area (at most 8, one for both plans, `cufft_work`).
module veslide_memory
    use veslide_kinds, only: dp, i8
    use veslide_config, only: config_t
    use veslide_solver, only: pdr_min_cells, default_anderson_memory
    use veslide_solver_options, only: SOLVER_DR, SOLVER_PDR
    implicit none
    private
    public :: memory_estimate_bytes, device_estimate_bytes, format_gib

    !> Libraries, FFTW plans, HDF5 buffers and the program itself [bytes]
    integer(i8), parameter :: fixed_bytes = 16_i8*1024*1024
    !> On the device: the runtime's own and the row partials [bytes]
    integer(i8), parameter :: device_fixed_bytes = 64_i8*1024*1024
    !> cuFFT's work area of a D2Z and a Z2D plan sharing it, at most [bytes per cell]
    real(dp), parameter :: cufft_work = 8.0_dp

contains

    !> Peak memory of the case or study of `cfg` on its grid [bytes]; with `ranks`, of one of that
    !> many processes sharing the grid (its rows, plus FFTW's MPI transposes: one more complex
    !> half-spectrum of its share, 8 bytes per cell)
    !> With `device`, a case solved on the device: the host's share (its solver's arrays are there)
    pure integer(i8) function memory_estimate_bytes(cfg, ranks, device) result(bytes)
        type(config_t), intent(in) :: cfg
        integer, intent(in), optional :: ranks
        logical, intent(in), optional :: device
        real(dp) :: n, solve, solver, analysis, kernel_build, study, per_cell
        n = real(cfg%grid%nx, dp)*real(cfg%grid%ny, dp)
        solve = 8 + 8 + 16 + 24
        ! per solver: pk 16, bccg 36, dr 40 + 8 m, pdr 41 (+ 16 + 8 m with mixing)
        solver = solver_bytes(cfg, [16.0_dp, 36.0_dp, 40.0_dp, 41.0_dp])
        if (present(device)) then
            if (device) solver = 0
        end if
        analysis = 8
        if (cfg%analysis%patches) analysis = analysis + 32
        if (cfg%analysis%persson) analysis = analysis + 24
        kernel_build = 8 + 16
        if (cfg%solver%kernel == 'collocation-alias' .or. cfg%solver%kernel == 'galerkin') kernel_build = 8 + 32
        study = 0
        if (cfg%sweep%is_study()) study = 8*max(1, size(cfg%sweep%speeds)) + 16 + 16
        per_cell = solve + max(solver, analysis, kernel_build, 16.0_dp) + study
        if (present(ranks)) then
            if (ranks > 1) then
                per_cell = per_cell + 8
                n = n/ranks
            end if
        end if
        bytes = fixed_bytes + int(per_cell*n, i8)

    end function memory_estimate_bytes

    !> Device memory a solve of the case of `cfg` holds at its peak [bytes] (veslide_device: what
    !> the heading lists), the method 'auto' takes as veslide_solver does
    pure integer(i8) function device_estimate_bytes(cfg) result(bytes)
        type(config_t), intent(in) :: cfg
        real(dp) :: n, per_cell
        n = real(cfg%grid%nx, dp)*real(cfg%grid%ny, dp)
        ! per solver: bccg 29 (pk does not run there: bccg's), dr 40 + 8 m, pdr 37 (+ 16 + 8 m)
        per_cell = 8 + 8 + 16 + 24 + solver_bytes(cfg, [29.0_dp, 29.0_dp, 40.0_dp, 37.0_dp]) + cufft_work
        bytes = device_fixed_bytes + int(per_cell*n, i8)
    end function device_estimate_bytes

    !> The bytes per cell of the solver the case of `cfg` runs, 'auto' taken as veslide_solver takes
    !> it (bccg for a symmetric kernel, pdr from pdr_min_cells cells, dr below), from the fixed
    !> parts `base` = [pk, bccg, dr, pdr]: dr adds 8 m for its Anderson history, pdr 16 + 8 m when
    !> it mixes (m > 0)
    pure real(dp) function solver_bytes(cfg, base) result(b)
        type(config_t), intent(in) :: cfg
        real(dp), intent(in) :: base(4)
        logical :: symmetric
        symmetric = cfg%material%model == 'elastic' .or. (cfg%motion%speed_m_s == 0.0_dp .and. &
                                                          size(cfg%sweep%speeds) == 0)
        select case (cfg%solver%method)
        case ('pk')
            b = base(1)
        case ('bccg')
            b = base(2)
        case ('dr')
            b = dr()
        case ('pdr')
            b = pdr()
        case default
            if (symmetric) then
                b = base(2)
            else if (real(cfg%grid%nx, dp)*real(cfg%grid%ny, dp) >= real(pdr_min_cells, dp)) then
                b = pdr()
            else
                b = dr()
            end if
        end select
    contains
        pure real(dp) function dr()
            dr = base(3) + 8*default_anderson_memory(SOLVER_DR, cfg%solver%anderson_memory)
        end function dr
        pure real(dp) function pdr()
            integer :: m
            m = default_anderson_memory(SOLVER_PDR, cfg%solver%anderson_memory)
            pdr = base(4)
            if (m > 0) pdr = pdr + 16 + 8*m
        end function pdr
    end function solver_bytes

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
