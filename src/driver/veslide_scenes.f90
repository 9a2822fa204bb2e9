!> Named scenes: the hard cases every solver change is measured on (`veslide-bench hard`, and
!> the `hard` test suite at a small grid). All share the paper's geometry (L0 = 1 cm, spectrum
!> q0 .. k_cut q0, rms slope 0.025) and material time tau = 10 ms, so v tau/L0 = speed [m/s].
!> The profiles (`profile_case`): many one-row and stripe-like random profiles, on which a solver
!> that converges on every 2-D scene can still stall (the `hard` suite runs each method on all).
!> The layered scenes (`layer_case`): thin and thick layers on both bases, Poisson ratios 0.3 to
!> 1/2, q0 d from 1e-3 to 20, elastic and viscoelastic (a thin bonded incompressible layer
!> stiffens the long waves as 1/(q d)^3, on which `dr` once stalled without contact).
module veslide_scenes
    use veslide_kinds, only: dp, two_pi
    use veslide_error, only: error_t
    use veslide_config, only: config_t, default_config, complete_config
    implicit none
    private
    public :: hard_case_count, hard_case, profile_case_count, profile_case, layer_case_count, layer_case

    integer, parameter :: ncase = 29
    !> profiles: one-row (nx 64, ny 1), stripes of 4 rows (eccentricity 0.1 along x) and of
    !> 8 rows (eccentricity 0.2 across x)
    integer, parameter :: nrow1 = 150, nstripe4 = 75, nstripe8 = 75
    !> layered scenes: q0 d (q0 = 2 pi/L0, L0 = 1 cm) x Poisson ratio x base x (elastic, viscoelastic)
    real(dp), parameter :: layer_q0d(6) = [1.0e-3_dp, 5.0e-3_dp, 2.0e-2_dp, 0.2_dp, 2.0_dp, 20.0_dp]
    real(dp), parameter :: layer_nu(3) = [0.3_dp, 0.45_dp, 0.5_dp]
    character(len=*), parameter :: layer_bases(2) = [character(len=12) :: 'bonded', 'frictionless']
    !> their speeds (viscoelastic, cycling with the case) [m/s]: below, at and above the loss peak
    real(dp), parameter :: layer_speeds(3) = [1.0e-2_dp, 0.13_dp, 1.0_dp]
    !> surfaces per layer (consecutive seeds, cycling over 1..20)
    integer, parameter :: layer_seeds = 5

contains

    pure integer function hard_case_count() result(n)
        n = ncase
    end function hard_case_count

    !> Configuration of hard case k (1..hard_case_count()) on an n x n grid; `name` describes it
    subroutine hard_case(k, n, cfg, name, error)
        integer, intent(in) :: k, n
        type(config_t), intent(out) :: cfg
        character(len=:), allocatable, intent(out) :: name
        type(error_t), allocatable, intent(out) :: error
        real(dp), parameter :: speeds(7) = [0.0_dp, 1.0e-3_dp, 1.0e-2_dp, 1.0e-1_dp, 1.0_dp, 10.0_dp, 1.0e3_dp]
        character(len=8), parameter :: speed_names(7) = [character(len=8) :: '0', '1e-3', '1e-2', '1e-1', '1', &
                                                          '10', '1e3']
        real(dp), parameter :: loads(5) = [1.0e3_dp, 1.0e4_dp, 3.0e5_dp, 3.0e6_dp, 1.0e8_dp]
        character(len=8), parameter :: load_names(5) = [character(len=8) :: '1e3', '1e4', '3e5', '3e6', '1e8']
        integer :: j
        call default_config(cfg, 'hard-case')
        cfg%grid%nx = n; cfg%grid%ny = n; cfg%grid%lx_m = 0.01_dp; cfg%grid%ly_m = 0.01_dp
        cfg%surface%k_cut = min(64.0_dp, n/4.0_dp)
        cfg%material%model = 'one_term'; cfg%material%einf_pa = 1.0e8_dp; cfg%material%ratio = 11.0_dp
        cfg%material%tau_s = 0.01_dp; cfg%material%poisson = 0.5_dp
        cfg%load%mean_pressure_pa = 32.0e3_dp; cfg%motion%speed_m_s = 0.13_dp
        cfg%solver%fft_planner = 'estimate'; cfg%output%fields = .false.
        cfg%output%file = 'hard.h5'
        select case (k)
        case (1:7)              ! ratio 11 across the loss peak and both limits
            cfg%motion%speed_m_s = speeds(k)
            name = 'ratio 11, v tau/L0 = '//trim(speed_names(k))
        case (8:14)             ! ratio 100
            cfg%material%ratio = 100.0_dp; cfg%motion%speed_m_s = speeds(k - 7)
            name = 'ratio 100, v tau/L0 = '//trim(speed_names(k - 7))
        case (15:21)            ! ratio 1000
            cfg%material%ratio = 1000.0_dp; cfg%motion%speed_m_s = speeds(k - 14)
            name = 'ratio 1000, v tau/L0 = '//trim(speed_names(k - 14))
        case (22:26)            ! contact fractions from a fraction of a percent to full contact
            cfg%load%mean_pressure_pa = loads(k - 21)
            name = 'ratio 11, v tau/L0 = 0.13, p = '//trim(load_names(k - 21))//' Pa'
        case (27)
            cfg%surface%eccentricity = 0.1_dp; cfg%surface%alpha_deg = 45.0_dp
            name = 'eccentricity 0.1 at 45 deg, ratio 11, v tau/L0 = 0.13'
        case (28)               ! 20 creep terms, retardation times 1e-8 .. 1e4 s, Einf/E0 = 100
            cfg%material%model = 'creep'; cfg%material%e0_pa = 1.0e6_dp
            cfg%material%prony_time_s = [(10.0_dp**(-8.0_dp + 12.0_dp*(j - 1)/19.0_dp), j = 1, 20)]
            cfg%material%prony_coef = [(((1.0_dp/1.0e6_dp - 1.0_dp/1.0e8_dp)/20.0_dp), j = 1, 20)]
            name = '20-term creep series over 12 decades, v = 0.13 m/s'
        case (29)
            cfg%surface%hurst = 0.3_dp
            name = 'Hurst 0.3, ratio 11, v tau/L0 = 0.13'
        end select
        call complete_config(cfg, error)
    end subroutine hard_case

    pure integer function profile_case_count() result(n)
        n = nrow1 + nstripe4 + nstripe8
    end function profile_case_count

    !> Configuration of profile k (1..profile_case_count()) solved by `method`, of an elastic
    !> solid or (`viscoelastic`) of the one-term law at v tau/L0 = 0.13: a random profile of
    !> seed k (one-row) or k - offset (stripes), the load cycling over 1e3, 3.2e4 and 3e5 Pa
    !> (contact fractions from about 0.3 % to 30 %)
    subroutine profile_case(k, method, viscoelastic, cfg, name, error)
        integer, intent(in) :: k
        character(len=*), intent(in) :: method
        logical, intent(in) :: viscoelastic
        type(config_t), intent(out) :: cfg
        character(len=:), allocatable, intent(out) :: name
        type(error_t), allocatable, intent(out) :: error
        real(dp), parameter :: loads(3) = [1.0e3_dp, 32.0e3_dp, 3.0e5_dp]
        character(len=32) :: text
        integer :: ny, seed
        call default_config(cfg, 'profile')
        if (k <= nrow1) then
            ny = 1; seed = k
        else if (k <= nrow1 + nstripe4) then
            ny = 4; seed = k - nrow1
            cfg%surface%eccentricity = 0.1_dp; cfg%surface%alpha_deg = 0.0_dp
        else
            ny = 8; seed = k - nrow1 - nstripe4
            cfg%surface%eccentricity = 0.2_dp; cfg%surface%alpha_deg = 90.0_dp
        end if
        cfg%grid%nx = merge(64, 128, ny == 1); cfg%grid%ny = ny
        cfg%grid%lx_m = 0.01_dp; cfg%grid%ly_m = 0.01_dp*ny/cfg%grid%nx
        cfg%surface%seed = seed; cfg%surface%k_cut = 16.0_dp
        cfg%load%mean_pressure_pa = loads(modulo(k, 3) + 1)
        call scene_solid(cfg, viscoelastic, 0.13_dp, method, 'profile.h5')
        write (text, '(i0, " x ", i0, ", seed ", i0, ", ", es8.1, " Pa")') cfg%grid%nx, ny, seed, &
            cfg%load%mean_pressure_pa
        name = trim(method)//' on the profile '//trim(text)
        call complete_config(cfg, error)
    end subroutine profile_case

    pure integer function layer_case_count() result(n)
        n = layer_seeds*size(layer_q0d)*size(layer_nu)*size(layer_bases)*2
    end function layer_case_count

    !> Configuration of layered scene k (1..layer_case_count()) solved by `method`: the hard
    !> cases' geometry at 64^2 (L0 = 1 cm, k_cut 16, 32 kPa), a layer of thickness d with
    !> q0 d = 1e-3 .. 20 on a 'bonded' or 'frictionless' base, Poisson ratio 0.3, 0.45 or 1/2;
    !> the first half elastic (E = 1e7 Pa), the second the one-term law (Einf = 1e8 Pa, ratio 11,
    !> tau = 10 ms) at 0.01, 0.13 or 1 m/s (cycling with k); each layer on `layer_seeds`
    !> surfaces, the seed cycling over 1..20 with k
    subroutine layer_case(k, method, cfg, name, error)
        integer, intent(in) :: k
        character(len=*), intent(in) :: method
        type(config_t), intent(out) :: cfg
        character(len=:), allocatable, intent(out) :: name
        type(error_t), allocatable, intent(out) :: error
        character(len=40) :: law
        character(len=120) :: text
        integer :: i, iq, inu, ibase
        logical :: viscoelastic
        i = (k - 1)/layer_seeds
        iq = modulo(i, size(layer_q0d)) + 1; i = i/size(layer_q0d)
        inu = modulo(i, size(layer_nu)) + 1; i = i/size(layer_nu)
        ibase = modulo(i, size(layer_bases)) + 1; i = i/size(layer_bases)
        viscoelastic = i > 0
        call default_config(cfg, 'layer')
        cfg%grid%nx = 64; cfg%grid%ny = 64; cfg%grid%lx_m = 0.01_dp; cfg%grid%ly_m = 0.01_dp
        cfg%surface%seed = modulo(k - 1, 20) + 1; cfg%surface%k_cut = 16.0_dp
        cfg%material%poisson = layer_nu(inu)
        cfg%material%thickness_m = layer_q0d(iq)*cfg%grid%lx_m/two_pi
        cfg%material%base = trim(layer_bases(ibase))
        cfg%load%mean_pressure_pa = 32.0e3_dp
        call scene_solid(cfg, viscoelastic, layer_speeds(modulo(k - 1, size(layer_speeds)) + 1), method, 'layer.h5')
        if (viscoelastic) then
            write (law, '("one-term at ", g0.2, " m/s")') cfg%motion%speed_m_s
        else
            law = 'elastic'
        end if
        write (text, '(a, ", ", a, " layer, q0 d = ", es7.1, ", nu = ", f4.2, ", seed ", i0)') trim(law), &
            trim(layer_bases(ibase)), layer_q0d(iq), layer_nu(inu), cfg%surface%seed
        name = trim(method)//' on '//trim(text)
        call complete_config(cfg, error)
    end subroutine layer_case

    !> The solid, solver and output of a profile or layer scene: the paper's one-term solid
    !> sliding at `speed` m/s (`viscoelastic`), or an elastic solid of 10 MPa at rest
    subroutine scene_solid(cfg, viscoelastic, speed, method, file)
        type(config_t), intent(inout) :: cfg
        logical, intent(in) :: viscoelastic
        real(dp), intent(in) :: speed
        character(len=*), intent(in) :: method, file
        if (viscoelastic) then
            cfg%material%model = 'one_term'; cfg%material%einf_pa = 1.0e8_dp; cfg%material%ratio = 11.0_dp
            cfg%material%tau_s = 0.01_dp; cfg%motion%speed_m_s = speed
        else
            cfg%material%model = 'elastic'; cfg%material%young_pa = 1.0e7_dp
        end if
        cfg%solver%method = method
        cfg%solver%fft_planner = 'estimate'; cfg%output%fields = .false.
        cfg%output%file = file
    end subroutine scene_solid

end module veslide_scenes
