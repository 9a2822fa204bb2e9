!> Parameter studies: every combination of the &sweep lists (seeds x eccentricities x angles x
!> pressures x speeds) in one run. Each surface is generated once, each speed's kernel built once
!> and reused, and the solver is warm-started along the speed axis (speeds are visited in the
!> order given). Every finished case is written at once under /cases/NNNNNN with its parameters,
!> and appended as a row of /summary (every parameter and scalar), then flushed; with several seeds,
!> /ensemble holds the mean and standard error over seeds of every scalar.
module veslide_sweep
    use, intrinsic :: iso_fortran_env, only: stdout => output_unit
    use veslide_kinds, only: dp, i8, pi
    use veslide_error, only: error_t
    use veslide_config, only: config_t
    use veslide_fftw, only: fft2d_t
    use veslide_kernel, only: kernel_t
    use veslide_material, only: material_t
    use veslide_hdf5, only: h5file_t
    use veslide_run, only: case_t, build_surface, build_material, build_case_kernel, solve_prepared, &
                           case_scalars, write_provenance, write_case_group, wall_seconds
    implicit none
    private
    public :: run_sweep, seed_statistics

    integer, parameter :: nparam = 6
    character(len=32), parameter :: param_names(nparam) = [character(len=32) :: 'case', 'seed', 'eccentricity', &
                                                           'alpha_deg', 'pressure_pa', 'speed_m_s']

contains

    !> Run the study of `cfg` into the (temporary) HDF5 file `path`; `nfail` counts cases that
    !> did not converge
    subroutine run_sweep(cfg, path, nfail, error, quiet, part)
        type(config_t), intent(inout) :: cfg
        character(len=*), intent(in) :: path
        integer, intent(out) :: nfail
        type(error_t), allocatable, intent(out) :: error
        logical, intent(in), optional :: quiet
        !> [rank, nranks]: run only the speed chains (seed, eccentricity, angle, pressure) whose
        !> index is rank modulo nranks; case numbers stay global (the batch driver uses it)
        integer, intent(in), optional :: part(2)
        real(dp), allocatable :: speeds(:), alphas(:), eccs(:), pressures(:), table(:, :), values(:), p_prev(:, :)
        real(dp), allocatable :: g_prev(:, :)
        integer(i8), allocatable :: seeds(:)
        character(len=32), allocatable :: names(:), columns(:)
        character(len=8), allocatable :: units(:)
        logical, allocatable :: is_int(:)
        type(kernel_t), allocatable :: kernels(:)
        real(dp), allocatable :: kernel_seconds(:)
        type(material_t) :: mat
        type(fft2d_t) :: fft
        type(h5file_t) :: f
        type(case_t) :: c
        real(dp), allocatable :: h(:, :)
        real(dp) :: t_start, t_case
        integer :: is, ie, ia, ip, iv, ncase, k, ncol, chain, rank, nranks, ndone, nmine
        character(len=16) :: tag
        logical :: quiet_, have_surface

        quiet_ = .false.; if (present(quiet)) quiet_ = quiet
        nfail = 0
        speeds = list_or(cfg%sweep_speeds, cfg%speed_m_s)
        alphas = list_or(cfg%sweep_alphas, cfg%alpha_deg)
        eccs = list_or(cfg%sweep_eccs, cfg%eccentricity)
        pressures = list_or(cfg%sweep_pressures, cfg%mean_pressure_pa)
        if (size(cfg%sweep_seeds) > 0) then
            seeds = cfg%sweep_seeds
        else
            seeds = [cfg%seed]
        end if
        ncase = size(speeds)*size(alphas)*size(eccs)*size(pressures)*size(seeds)
        rank = 0; nranks = 1
        if (present(part)) then
            rank = part(1); nranks = max(1, part(2))
        end if
        nmine = 0
        do chain = 1, ncase/size(speeds)
            if (modulo(chain - 1, nranks) == rank) nmine = nmine + size(speeds)
        end do

        call build_material(cfg, mat, error); if (allocated(error)) return
        ! a measured topography fixes the grid and the cell size, which the kernels need
        if (cfg%surface_kind == 'file') then
            call build_surface(cfg, fft, h, error); if (allocated(error)) return
        end if
        allocate (kernels(size(speeds)), kernel_seconds(size(speeds)))
        do iv = 1, size(speeds)
            cfg%speed_m_s = speeds(iv)
            call build_case_kernel(cfg, mat, kernels(iv), kernel_seconds(iv), error); if (allocated(error)) return
        end do
        call f%open(path, 'w', error); if (allocated(error)) return
        call write_provenance(f, cfg, error); if (allocated(error)) return
        call fft%init(cfg%nx, cfg%ny, error, planner=cfg%fft_planner, nthreads=cfg%threads)
        if (allocated(error)) return

        t_start = wall_seconds()
        k = 0; chain = 0; ndone = 0
        do is = 1, size(seeds)
            do ie = 1, size(eccs)
                do ia = 1, size(alphas)
                    cfg%seed = seeds(is); cfg%eccentricity = eccs(ie); cfg%alpha_deg = alphas(ia)
                    have_surface = .false.
                    do ip = 1, size(pressures)
                        cfg%mean_pressure_pa = pressures(ip)
                        chain = chain + 1
                        if (modulo(chain - 1, nranks) /= rank) then
                            k = k + size(speeds); cycle
                        end if
                        if (.not. have_surface .and. cfg%surface_kind /= 'file') then
                            call build_surface(cfg, fft, h, error); if (allocated(error)) return
                            have_surface = .true.
                        end if
                        do iv = 1, size(speeds)
                            k = k + 1; ndone = ndone + 1
                            cfg%speed_m_s = speeds(iv)
                            c%h = h; c%mat = mat; c%kernel = kernels(iv); c%kernel_seconds = kernel_seconds(iv)
                            t_case = wall_seconds()
                            if (iv > 1 .and. cfg%sweep_warm_start) then
                                call solve_prepared(cfg, fft, c, error, p_init=p_prev, g_init=g_prev)
                            else
                                call solve_prepared(cfg, fft, c, error)
                            end if
                            if (allocated(error)) return
                            p_prev = c%state%p; g_prev = c%state%g
                            if (.not. c%state%converged) nfail = nfail + 1
                            write (tag, '("/cases/",i6.6)') k
                            call write_case_group(f, trim(tag), cfg, c, error); if (allocated(error)) return
                            call f%write(trim(tag)//'/parameters', [real(k, dp), real(seeds(is), dp), eccs(ie), &
                                                                    alphas(ia), pressures(ip), speeds(iv)], error)
                            if (allocated(error)) return
                            call f%writeattr(trim(tag)//'/parameters', 'columns', &
                                             'case, seed, eccentricity, alpha_deg, pressure_pa, speed_m_s', error)
                            if (allocated(error)) return
                            call case_scalars(cfg, c, names, units, values, is_int)
                            if (.not. allocated(table)) then
                                ncol = nparam + size(names)
                                allocate (table(ncol, ncase), columns(ncol))
                                columns(1:nparam) = param_names; columns(nparam + 1:) = names
                                table = 0.0_dp
                            end if
                            table(1:nparam, k) = [real(k, dp), real(seeds(is), dp), eccs(ie), alphas(ia), &
                                                  pressures(ip), speeds(iv)]
                            table(nparam + 1:, k) = values(1:ncol - nparam)
                            call f%append_row('/summary', columns, table(:, k), error); if (allocated(error)) return
                            call f%flush()
                            if (.not. quiet_) call progress(ndone, nmine, t_start, wall_seconds() - t_case, &
                                                            seeds(is), eccs(ie), alphas(ia), pressures(ip), speeds(iv), c)
                        end do
                    end do
                end do
            end do
        end do
        if (size(seeds) > 1 .and. nranks == 1) call write_ensemble(f, columns, table, size(seeds), error)
        if (allocated(error)) return
        call f%close()
        call fft%destroy()

    contains

        function list_or(list, single) result(v)
            real(dp), intent(in) :: list(:), single
            real(dp), allocatable :: v(:)
            if (size(list) > 0) then
                v = list
            else
                v = [single]
            end if
        end function list_or

    end subroutine run_sweep

    subroutine progress(k, n, t_start, t_case, seed, ecc, alpha, p, v, c)
        integer, intent(in) :: k, n
        real(dp), intent(in) :: t_start, t_case, ecc, alpha, p, v
        integer(i8), intent(in) :: seed
        type(case_t), intent(in) :: c
        real(dp) :: elapsed
        elapsed = wall_seconds() - t_start
        write (stdout, '("case ",i0,"/",i0,": seed ",i0,", eps ",f5.3,", alpha ",f6.1," deg, p ",es9.3, &
            &" Pa, v ",es9.3," m/s: area ",f8.5,", f ",es10.3,", ",i0," FFT pairs",a,", ",f7.2," s; elapsed ",f8.1, &
            &" s, left ~",f8.1," s")') k, n, seed, ecc, alpha, p, v, count(c%state%p > 0.0_dp)/real(size(c%state%p), dp), &
            -dot_product(c%force_pa, unit_or_x(c%velocity_m_s))/p, c%state%operator_applications, &
            trim(merge('               ', ', NOT CONVERGED', c%state%converged)), t_case, elapsed, elapsed/k*(n - k)
        flush (stdout)
    end subroutine progress

    pure function unit_or_x(v) result(u)
        real(dp), intent(in) :: v(2)
        real(dp) :: u(2)
        u = [1.0_dp, 0.0_dp]
        if (norm2(v) > 0.0_dp) u = v/norm2(v)
    end function unit_or_x

    !> Mean and standard error over seeds of every scalar, one row per parameter combination.
    !> Rows of the summary are ordered seed-major, so row r of seed s is r + (s - 1) m.
    subroutine write_ensemble(f, columns, table, nseed, error)
        type(h5file_t), intent(inout) :: f
        character(len=32), intent(in) :: columns(:)
        real(dp), intent(in) :: table(:, :)
        integer, intent(in) :: nseed
        type(error_t), allocatable, intent(out) :: error
        character(len=32), allocatable :: ecols(:)
        real(dp), allocatable :: e(:, :), x(:)
        integer :: m, r, j, ncol, nv, kk
        ncol = size(columns); m = size(table, 2)/nseed; nv = ncol - nparam
        allocate (ecols(4 + 2*nv), e(4 + 2*nv, m))
        ecols(1:4) = param_names(3:6)
        do j = 1, nv
            ecols(4 + j) = 'mean_'//trim(columns(nparam + j))
            ecols(4 + nv + j) = 'sem_'//trim(columns(nparam + j))
        end do
        do r = 1, m
            e(1:4, r) = table(3:6, r)
            do j = 1, nv
                x = table(nparam + j, [(r + (kk - 1)*m, kk = 1, nseed)])
                call seed_statistics(x, axial_kind(columns(nparam + j)), e(4 + j, r), e(4 + nv + j, r))
            end do
        end do
        call f%write_table('/ensemble', ecols, e, error)
    end subroutine write_ensemble

    !> Directions of axes, defined modulo pi: 1 for angles in [0, pi) (theta of a tensor, patch
    !> axes), 2 for angles in (-pi/2, pi/2] (phi of eq. 16), 0 for ordinary quantities
    pure integer function axial_kind(name) result(kind)
        character(len=*), intent(in) :: name
        kind = 0
        if (any(trim(name) == [character(len=16) :: 'theta_s_rad', 'theta_d_rad', 'patch_theta_rad'])) kind = 1
        if (trim(name) == 'phi_rad') kind = 2
    end function axial_kind

    !> Mean and standard error of the mean over seeds. Axial data (angles modulo pi, `axial` 1 or
    !> 2 as in axial_kind) use the circular mean of the doubled angle, atan2(<sin 2x>, <cos 2x>)/2,
    !> in the range of the quantity, and deviations wrapped into (-pi/2, pi/2]: an axis scattering
    !> about 0 = pi averages to 0, not to pi/2.
    pure subroutine seed_statistics(x, axial, mean, sem)
        real(dp), intent(in) :: x(:)
        integer, intent(in) :: axial
        real(dp), intent(out) :: mean, sem
        real(dp) :: d(size(x))
        integer :: n
        n = size(x)
        if (axial > 0) then
            mean = 0.5_dp*atan2(sum(sin(2*x)), sum(cos(2*x)))      ! in (-pi/2, pi/2]
            if (axial == 1) mean = modulo(mean, pi)
            d = x - mean
            d = d - pi*anint(d/pi)
        else
            mean = sum(x)/n
            d = x - mean
        end if
        sem = sqrt(sum(d**2)/max(1, n - 1))/sqrt(real(n, dp))
    end subroutine seed_statistics

end module veslide_sweep
